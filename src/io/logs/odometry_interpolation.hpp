// Private to slamkit_io: the odometry at a scan's timestamp, shared by the laser-log readers
// (CARMEN, ROS bags).
#pragma once

#include <algorithm>

#include "slamkit/core/angle.hpp"
#include "slamkit/core/trajectory.hpp"

namespace slamkit::io_detail {

// The pose at t_s between the records of `odometry` (sorted by time, not empty) that bracket it:
// linear in x and y, along the shorter arc in heading; the nearest record outside their span.
inline Pose2 InterpolateOdometry(const Trajectory& odometry, double t_s) {
  const auto after = std::upper_bound(
      odometry.begin(), odometry.end(), t_s,
      [](double t, const StampedPose& record) { return t < record.t_s; });
  if (after == odometry.begin()) return after->pose;
  if (after == odometry.end()) return odometry.back().pose;
  const StampedPose& a = *(after - 1);
  const StampedPose& b = *after;
  const double s = (t_s - a.t_s) / (b.t_s - a.t_s);  // b.t_s > t_s >= a.t_s
  return Pose2(a.pose.x() + s * (b.pose.x() - a.pose.x()),
               a.pose.y() + s * (b.pose.y() - a.pose.y()),
               a.pose.theta() + s * WrapAngle(b.pose.theta() - a.pose.theta()));
}

}  // namespace slamkit::io_detail
