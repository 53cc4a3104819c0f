#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

#include <fmt/format.h>

namespace slamkit::app {

Progress::Progress(std::string label, int total)
    : label_(std::move(label)), total_(total), tty_(isatty(fileno(stderr)) != 0) {}

void Progress::Update(int done) {
  const int width = 30;
  const int filled = total_ > 0 ? done * width / total_ : width;
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string rate =
      elapsed_s > 0.0 ? fmt::format(", {:.0f} {}/s", done / elapsed_s, label_) : "";
  if (tty_) {
    fmt::print(stderr, "\r{} [{:=<{}}{: <{}}] {}/{}{}", label_, "", filled, "", width - filled,
               done, total_, rate);
    if (done >= total_) fmt::print(stderr, "\n");
    std::fflush(stderr);
    return;
  }
  const int decile = total_ > 0 ? done * 10 / total_ : 10;
  if (decile != last_decile_) {
    last_decile_ = decile;
    fmt::print(stderr, "{}: {}/{}{}\n", label_, done, total_, rate);
  }
}

}  // namespace slamkit::app
