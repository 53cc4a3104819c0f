#include "carmen_records.hpp"

#include <fmt/format.h>

#include <cfloat>
#include <cstddef>
#include <iterator>
#include <limits>
#include <string_view>

#include "slamkit/core/angle.hpp"

namespace slamkit::carmen {

using text::Fields;

namespace {

constexpr const char* kOdomFields[] = {"x",         "y",    "theta",           "tv", "rv", "accel",
                                       "timestamp", "host", "logger_timestamp"};
constexpr const char* kFlaserPoseFields[] = {"x", "y", "theta", "odom_x", "odom_y", "odom_theta"};
constexpr const char* kRobotLaserHead[] = {"laser_type", "start_angle", "fov",
                                           "angular_resolution", "max_range", "accuracy",
                                           "remission_mode", "num_readings"};
constexpr const char* kRobotLaserTail[] = {
    "laser_x", "laser_y", "laser_theta", "robot_x", "robot_y", "robot_theta", "tv", "rv",
    "forward_safety_dist", "side_safety_dist", "turn_axis", "timestamp", "host",
    "logger_timestamp"};
constexpr std::size_t kRobotLaserTailSize = std::size(kRobotLaserTail);

// A number of magnitude at most kCarmenMaxMagnitude (metres or radians).
double Bounded(const Fields& fields, std::size_t i, const text::FieldName& field) {
  const double value = fields.Number(i, field);
  if (std::abs(value) > kCarmenMaxMagnitude) {
    fields.Fail(field, fmt::format("magnitude above {:g} ('{}')", kCarmenMaxMagnitude,
                                   fields.Text(i)));
  }
  return value;
}

// Reads the pose stored as x, y, theta in fields first .. first + 2.
Pose2 PoseAt(const Fields& fields, std::size_t first, const char* const* names) {
  return Pose2(Bounded(fields, first, {names[0]}), Bounded(fields, first + 1, {names[1]}),
               Bounded(fields, first + 2, {names[2]}));
}

// A timestamp of magnitude at most kCarmenMaxTimestampS.
double Timestamp(const Fields& fields, std::size_t i) {
  const double value = fields.Number(i, {"timestamp"});
  if (std::abs(value) > kCarmenMaxTimestampS) {
    fields.Fail({"timestamp"}, fmt::format("magnitude above {:g} s ('{}')", kCarmenMaxTimestampS,
                                           fields.Text(i)));
  }
  return value;
}

float Range(const Fields& fields, std::size_t i, int beam) {
  const double value = fields.Number(i, {"r", beam});
  if (value < 0.0) fields.Fail({"r", beam}, fmt::format("negative range ('{}')", fields.Text(i)));
  if (std::abs(value) > FLT_MAX) fields.Fail({"r", beam}, "out of range");
  return static_cast<float>(value);
}

// A positive maximum range of at most kCarmenMaxMagnitude metres.
double MaxRange(const Fields& fields, std::size_t i, const text::FieldName& field) {
  const double value = Bounded(fields, i, field);
  if (value <= 0.0) {
    fields.Fail(field, fmt::format("max range must be positive ('{}')", fields.Text(i)));
  }
  return value;
}

}  // namespace

std::pair<std::string, std::string> ParseParam(const Fields& fields, FrontLaser* laser) {
  constexpr const char* kNames[] = {"name", "value"};
  if (fields.size() < 2) fields.Fail({kNames[fields.size()]}, "missing");
  std::pair<std::string, std::string> param(fields.Text(0), fields.Text(1));
  const std::string_view name = param.first;
  if (name == "laser_front_laser_fov") {
    // CARMEN documents degrees, but some logs (csail) give radians: no laser sees less than 2π°.
    const double fov = fields.Number(1, {"value"});
    if (fov <= 0.0 || fov > 360.0) {
      fields.Fail({"value"}, fmt::format("laser_front_laser_fov must be in (0, 360] degrees (or "
                                         "(0, 2π] radians), got '{}'",
                                         fields.Text(1)));
    }
    laser->fov_rad = fov > 2.0 * M_PI ? DegToRad(fov) : fov;
  } else if (name == "laser_front_laser_max_range") {
    laser->max_range_m = MaxRange(fields, 1, {"value"});
    laser->max_range_from_laser_param = true;
  } else if (name == "robot_front_laser_max" && !laser->max_range_from_laser_param) {
    laser->max_range_m = MaxRange(fields, 1, {"value"});
  } else if (name == "robot_frontlaser_offset") {
    laser->offset = Pose2(Bounded(fields, 1, {"value"}), 0.0, 0.0);
  }
  return param;
}

StampedPose ParseOdom(const Fields& fields) {
  fields.Expect(std::size(kOdomFields), kOdomFields);
  for (std::size_t i = 3; i < 6; ++i) fields.Number(i, {kOdomFields[i]});
  fields.Number(8, {"logger_timestamp"});
  return {Timestamp(fields, 6), PoseAt(fields, 0, kOdomFields)};
}

LaserScan ParseFlaser(const Fields& fields, const FrontLaser& laser) {
  if (fields.size() == 0) fields.Fail({"n"}, "missing");
  const int n = fields.Count(0, {"n"});
  if (n == 0) fields.Fail({"n"}, "no readings (a scan needs at least one beam)");
  const std::size_t expected = static_cast<std::size_t>(n) + 10;
  if (fields.size() != expected) {
    fields.Fail({"n"}, fmt::format("{} readings need {} fields after FLASER, got {}", n, expected,
                                   fields.size()));
  }
  LaserScan scan;
  scan.ranges_m.resize(n);
  for (int i = 0; i < n; ++i) scan.ranges_m[i] = Range(fields, 1 + i, i + 1);
  const std::size_t pose = static_cast<std::size_t>(n) + 1;
  scan.logged_pose = PoseAt(fields, pose, kFlaserPoseFields);
  scan.odometry = PoseAt(fields, pose + 3, kFlaserPoseFields + 3);
  scan.t_s = Timestamp(fields, pose + 6);
  fields.Number(pose + 8, {"logger_timestamp"});
  // n even (180 beams at 1°): the beams start at -fov/2 and stop one increment short of +fov/2;
  // n odd (181 or 361 beams): both ends of the field of view are included.
  scan.angle_min_rad = -laser.fov_rad / 2.0;
  scan.angle_increment_rad = n > 1 && n % 2 == 1 ? laser.fov_rad / (n - 1) : laser.fov_rad / n;
  scan.max_range_m = laser.max_range_m.value_or(std::numeric_limits<double>::infinity());
  scan.laser_offset = laser.offset;
  return scan;
}

LaserScan ParseRobotLaser1(const Fields& fields) {
  const std::size_t head = std::size(kRobotLaserHead);
  if (fields.size() < head) fields.Fail({kRobotLaserHead[fields.size()]}, "missing");
  const int n = fields.Count(head - 1, {"num_readings"});
  if (n == 0) fields.Fail({"num_readings"}, "no readings (a scan needs at least one beam)");
  const std::size_t remissions = head + static_cast<std::size_t>(n);
  if (fields.size() <= remissions) fields.Fail({"num_remissions"}, "missing");
  const int m = fields.Count(remissions, {"num_remissions"});
  const std::size_t tail = remissions + 1 + static_cast<std::size_t>(m);
  if (fields.size() != tail + kRobotLaserTailSize) {
    fields.Fail({"num_readings"}, fmt::format("{} readings and {} remissions need {} fields after "
                                              "ROBOTLASER1, got {}",
                                              n, m, tail + kRobotLaserTailSize, fields.size()));
  }
  for (std::size_t i = 0; i + 1 < head; ++i) fields.Number(i, {kRobotLaserHead[i]});
  LaserScan scan;
  // Bounded like the poses: angles near 1e308 would make the later beams' angles infinite.
  scan.angle_min_rad = Bounded(fields, 1, {"start_angle"});
  scan.angle_increment_rad = Bounded(fields, 3, {"angular_resolution"});
  scan.max_range_m = MaxRange(fields, 4, {"max_range"});
  scan.ranges_m.resize(n);
  for (int i = 0; i < n; ++i) scan.ranges_m[i] = Range(fields, head + i, i + 1);
  for (int i = 0; i < m; ++i) fields.Number(remissions + 1 + i, {"rem", i + 1});
  const Pose2 laser = PoseAt(fields, tail, kRobotLaserTail);
  scan.logged_pose = PoseAt(fields, tail + 3, kRobotLaserTail + 3);
  scan.odometry = scan.logged_pose;
  scan.laser_offset = scan.logged_pose.Between(laser);
  for (std::size_t i = 6; i < 11; ++i) fields.Number(tail + i, {kRobotLaserTail[i]});
  scan.t_s = Timestamp(fields, tail + 11);
  fields.Number(tail + 13, {"logger_timestamp"});
  return scan;
}

}  // namespace slamkit::carmen
