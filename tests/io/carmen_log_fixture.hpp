// What the CARMEN reader's tests share: hand-written log records and a fixture that writes a log
// into the test's own folder and reads it back.
#pragma once

#include <filesystem>
#include <string>

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"
#include "slamkit/io/carmen_reader.hpp"

namespace slamkit::carmen_test {

inline std::string Odom(double x, double y, double theta, double t) {
  return "ODOM " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(theta) +
         " 0 0 0 " + std::to_string(t) + " host 0\n";
}

// Three beams; the pose fields say (9, 8, 0.7) so that a test sees which odometry was used.
inline std::string Flaser(double t) {
  return "FLASER 3 1.5 2.5 81.83 9 8 0.7 9 8 0.7 " + std::to_string(t) + " host 0\n";
}

class CarmenReader : public testing::TempDirTest {
 protected:
  std::filesystem::path Write(const std::string& text,
                              const std::string& name = "log.clf") const {
    return WriteFile(name, text);
  }
  std::string ErrorOf(const std::filesystem::path& path,
                      const CarmenReadOptions& options = {}) const {
    return testing::InputErrorOf([&] { ReadCarmenLog(path, options); });
  }
  std::string ErrorOfLog(const std::string& text) const { return ErrorOf(Write(text)); }
};

}  // namespace slamkit::carmen_test
