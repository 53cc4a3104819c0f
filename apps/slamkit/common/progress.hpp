#pragma once

#include <chrono>
#include <string>
#include <string_view>
#include <utility>

#include <fmt/format.h>

namespace slamkit::app {

// Writes `text` to stderr with write(2), bypassing stdio: never throws, and a closed, full or
// broken stderr (EBADF, ENOSPC, EPIPE) is ignored. Progress and error messages go through it.
void WriteStderr(std::string_view text) noexcept;

// fmt::print(stderr, ...) that never throws.
template <typename... T>
void PrintStderr(fmt::format_string<T...> format, T&&... args) noexcept {
  try {
    WriteStderr(fmt::format(format, std::forward<T>(args)...));
  } catch (...) {
  }
}

// A progress line on stderr with the elapsed time and, once enough time has passed to measure
// it, the rate (label per second) and an ETA: redrawn in place on a terminal, one line per 10 %
// otherwise (logs). Never throws.
class Progress {
 public:
  Progress(std::string label, int total);
  void Update(int done) noexcept;

 private:
  std::string label_;
  int total_;
  bool tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// "1:05" or "12.3 s" for a duration in seconds.
std::string FormatDuration(double seconds);

}  // namespace slamkit::app
