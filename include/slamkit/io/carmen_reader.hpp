#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/models/laser_scan.hpp"

namespace slamkit {

struct CarmenReadOptions {
  // Skip malformed lines (counting them) instead of failing on the first one.
  bool skip_bad_lines = false;
};

// A CARMEN log as one time-ordered stream: scans with the odometry interpolated at each scan's
// timestamp, the raw odometry records, and the PARAM settings.
struct CarmenLog {
  std::vector<LaserScan> scans;
  Trajectory odometry;                        // the ODOM records in log order
  std::map<std::string, std::string> params;  // PARAM name value
  int skipped_lines = 0;                      // with skip_bad_lines
};

// Reads ODOM, FLASER, ROBOTLASER1 and PARAM records (other records and `#` lines are ignored);
// gzip-compressed files (by content, not name) are read transparently. Throws InputError naming
// the file, line and field for a wrong beam count, a non-number, NaN/inf, or time going backwards,
// unless options.skip_bad_lines.
CarmenLog ReadCarmenLog(const std::filesystem::path& path, const CarmenReadOptions& options = {});

// One relation of Kümmerle et al. 2009: the pose at t2_s expressed in the frame of the pose at
// t1_s.
struct PoseRelation {
  double t1_s = 0.0;
  double t2_s = 0.0;
  Pose2 delta;
};

// Reads `t1 t2 x y z roll pitch yaw` lines (z, roll and pitch must be 0 for a 2D log within
// 1e-6). Throws InputError naming the file, line and field.
std::vector<PoseRelation> ReadRelations(const std::filesystem::path& path);

}  // namespace slamkit
