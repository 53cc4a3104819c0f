#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>

#include "slamkit/io/carmen_reader.hpp"

namespace slamkit {

// Where a ROS 1 bag keeps what a laser-SLAM run needs.
struct RosBagReadOptions {
  std::string scan_topic = "/scan";  // sensor_msgs/LaserScan
  std::string odom_topic = "/odom";  // nav_msgs/Odometry (unless odometry_from_tf)
  // Take the odometry from /tf's odom_frame -> base_frame transforms instead of odom_topic.
  bool odometry_from_tf = false;
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  // The laser's no-return range, when the user knows it better than the messages' range_max.
  std::optional<double> max_range_m;
};

// A ROS 1 bag as the laser log the CARMEN reader gives (CarmenLog: one structure for every laser
// log): the scans of scan_topic in the order the bag recorded them (their header stamps may
// jitter back, as a CARMEN log's do), each with the odometry at its header stamp, linear between
// the odometry samples that bracket it (sorted by stamp; the nearest outside their span; a
// sample at exactly the stamp is taken as it is, the last of several); the odometry samples by
// stamp; the laser's offset from /tf_static (or /tf) base_frame -> the scan's
// frame_id, else none (a note says so). Beam i points at angle_min + i · angle_increment, the
// messages' float32 values as LaserScanAngles takes them back. max_range_m is
// options.max_range_m, else the message's range_max: a reading at or above it is a no-return
// (counted in no_return_beams), and so is +inf, stored as max_range_m (REP 117); NaN, -inf and
// readings below range_min are no measurement, stored as NaN (a note counts them). Headings
// come from the quaternions' yaw.
//
// Throws InputError naming the file for a bag that cannot be opened or read (not a bag,
// truncated, unindexed), a topic that is missing or holds another message type (the topics the
// bag has are named), a scan without beams or with an angle increment or range_max that is not
// finite and positive, and a non-finite pose.
CarmenLog ReadRosBag(const std::filesystem::path& path, const RosBagReadOptions& options = {});

// A LaserScan's angle_min and angle_increment (float32) as the doubles a driver rounded to get
// them. Drivers compute them in double, nearly always as multiples of π: an increment of π/N (1°,
// 0.5°, 0.25°, 360°/1024) and an angle_min of whole half increments (−90°, −135°). The increment
// becomes π/N (N ≤ 100,000) and angle_min k·π/(2N) when they round to the message's values;
// otherwise both are kept as read. So a bag's beams point where the recording laser's did, to a
// double's precision: the bag of a CARMEN log gives that log's run.
std::pair<double, double> LaserScanAngles(float angle_min, float angle_increment);

}  // namespace slamkit
