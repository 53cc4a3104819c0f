#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "slamkit/core/pose2.hpp"

namespace slamkit {

// One planar laser scan. Beam i points at angle_min_rad + i · angle_increment_rad in the laser
// frame; a range of max_range_m or more means "no return" (free space up to a usable range, but
// never a hit). max_range_m is the sensor's, set by whoever makes the scan (the log reader, the
// simulator); the default, infinity, takes every finite positive reading for a return.
struct LaserScan {
  double t_s = 0.0;                     // the scan's timestamp as in the log
  std::vector<float> ranges_m;
  double angle_min_rad = -M_PI / 2.0;
  double angle_increment_rad = M_PI / 180.0;
  double max_range_m = std::numeric_limits<double>::infinity();
  Pose2 odometry;      // raw odometry pose at t_s (interpolated between ODOM records)
  Pose2 logged_pose;   // the pose the log gives with the scan (corrected in *-corrected logs)
  Pose2 laser_offset;  // the laser in the robot frame

  double BeamAngle(int i) const { return angle_min_rad + i * angle_increment_rad; }
  bool IsReturn(int i) const {
    return std::isfinite(ranges_m[i]) && ranges_m[i] > 0.0f && ranges_m[i] < max_range_m;
  }
};

}  // namespace slamkit
