#pragma once

// The CARMEN harnesses' shared part (carmen_fuzzer.cpp, carmen_gz_fuzzer.cpp): read the file
// twice, strict with the default options and lenient with the other code paths switched on, and
// check what carmen_reader.hpp promises about the result.

#include <cmath>
#include <filesystem>

#include "fuzz_input.hpp"
#include "slamkit/io/carmen_reader.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit::fuzz {

inline bool Finite(const Pose2& p) { return p.vector().allFinite(); }

inline void CheckLog(const CarmenLog& log) {
  Check(!log.scans.empty(), "a CARMEN log has at least one scan");
  for (const LaserScan& scan : log.scans) {
    Check(!scan.ranges_m.empty(), "a scan has at least one beam");
    for (float r : scan.ranges_m) Check(r >= 0.0f, "ranges are non-negative");
    Check(scan.max_range_m > 0.0, "max ranges are positive");
    const int last = static_cast<int>(scan.ranges_m.size()) - 1;
    Check(std::isfinite(scan.BeamAngle(0)) && std::isfinite(scan.BeamAngle(last)),
          "beam angles are finite");
    Check(Finite(scan.odometry) && Finite(scan.logged_pose) && Finite(scan.laser_offset),
          "scan poses are finite");
  }
}

inline void ReadBothWays(const std::filesystem::path& path) {
  try {
    CheckLog(ReadCarmenLog(path));
  } catch (const InputError&) {
  }
  CarmenReadOptions lenient;
  lenient.skip_bad_lines = true;
  lenient.odometry_from_scan_fields = false;  // interpolates the ODOM records
  try {
    CheckLog(ReadCarmenLog(path, lenient));
  } catch (const InputError&) {
  }
}

}  // namespace slamkit::fuzz
