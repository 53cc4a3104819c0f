#pragma once

#include <chrono>
#include <string>

namespace slamkit::app {

// A progress line on stderr with the rate so far (label per second): redrawn in place on a
// terminal, one line per 10 % otherwise (logs).
class Progress {
 public:
  Progress(std::string label, int total);
  void Update(int done);

 private:
  std::string label_;
  int total_;
  bool tty_;
  int last_decile_ = -1;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace slamkit::app
