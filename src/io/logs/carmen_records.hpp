#pragma once

// Private to slamkit_io: parsing the CARMEN records that ReadCarmenLog understands, from the
// fields of one line (text_records.hpp). Every error is an InputError `file:line: RECORD field
// 'name': reason ('token')`.

#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/core/trajectory.hpp"
#include "../text/text_records.hpp"

namespace slamkit::carmen {

// Bound on pose, odometry, offset and max-range values (metres or radians): larger magnitudes
// make no physical sense and would overflow downstream (see carmen_reader.hpp).
inline constexpr double kCarmenMaxMagnitude = 1e6;
// Bound on timestamps (seconds): 31 700 years, far above Unix time (1.7e9 s, the CARMEN clock).
// Without it, two timestamps near ±1e308 overflow the odometry interpolation into NaN poses.
inline constexpr double kCarmenMaxTimestampS = 1e12;

// The front-laser settings that a FLASER record leaves implicit, from the PARAM records so far.
struct FrontLaser {
  double fov_rad = M_PI;
  // The no-return range the PARAM records give, if any: laser_front_laser_max_range wins over
  // robot_front_laser_max.
  std::optional<double> max_range_m;
  bool max_range_from_laser_param = false;
  Pose2 offset;
};

// PARAM name value ...: the name and value; updates `laser` when the name is one of its settings
// (laser_front_laser_fov, laser_front_laser_max_range, robot_front_laser_max,
// robot_frontlaser_offset), whose value must then be a number.
std::pair<std::string, std::string> ParseParam(const text::Fields& fields, FrontLaser* laser);

// ODOM x y theta tv rv accel timestamp host logger_timestamp.
StampedPose ParseOdom(const text::Fields& fields);
// The scan records; in the result, odometry holds the record's own odometry fields (FLASER
// odom_x odom_y odom_theta, ROBOTLASER1 robot_x robot_y robot_theta).
LaserScan ParseFlaser(const text::Fields& fields, const FrontLaser& laser);
LaserScan ParseRobotLaser1(const text::Fields& fields);

}  // namespace slamkit::carmen
