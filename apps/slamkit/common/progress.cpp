#include "common/progress.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>

namespace slamkit::app {
namespace {

// A rate (and so an ETA) is shown only after this long: before, it measures start-up noise.
constexpr double kMinRateTimeS = 1.0;

}  // namespace

void WriteStderr(std::string_view text) noexcept {
  const char* p = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(STDERR_FILENO, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // EBADF, EPIPE, ENOSPC, ...: nowhere to report it
    p += n;
    left -= static_cast<std::size_t>(n);
  }
}

std::string FormatDuration(double seconds) {
  if (!(seconds >= 0.0) || !std::isfinite(seconds)) return "?";
  if (seconds < 60.0) return fmt::format("{:.1f} s", seconds);
  const auto s = static_cast<long long>(std::llround(seconds));
  if (s < 3600) return fmt::format("{}:{:02}", s / 60, s % 60);
  return fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60);
}

Progress::Progress(std::string label, int total)
    : label_(std::move(label)), total_(total), tty_(isatty(STDERR_FILENO) != 0) {}

void Progress::Update(int done) noexcept {
  try {
    const int width = 30;
    const int filled = total_ > 0 ? std::min(done, total_) * width / total_ : width;
    const double elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::string timing = fmt::format(", {} elapsed", FormatDuration(elapsed_s));
    if (elapsed_s >= kMinRateTimeS && done > 0) {
      const double rate = done / elapsed_s;
      // Slow items (whole runs) keep two significant digits rather than showing "0 runs/s".
      timing += rate >= 10.0 ? fmt::format(", {:.0f} {}/s", rate, label_)
                             : fmt::format(", {:.2g} {}/s", rate, label_);
      if (done < total_) timing += fmt::format(", ETA {}", FormatDuration((total_ - done) / rate));
    }
    if (tty_) {
      // \x1b[K clears what a longer previous line left.
      WriteStderr(fmt::format("\r{} [{:=<{}}{: <{}}] {}/{}{}\x1b[K{}", label_, "", filled, "",
                              width - filled, done, total_, timing, done >= total_ ? "\n" : ""));
      return;
    }
    const int decile = total_ > 0 ? done * 10 / total_ : 10;
    if (decile != last_decile_) {
      last_decile_ = decile;
      WriteStderr(fmt::format("{}: {}/{}{}\n", label_, done, total_, timing));
    }
  } catch (...) {
    // Progress is a courtesy: losing a line must not stop the run.
  }
}

}  // namespace slamkit::app
