#include "slamkit/planning/trajectory_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "slamkit/core/angle.hpp"

namespace slamkit {

Eigen::Vector2d StraightTrajectory::Position(double t_s) const {
  const double length = (goal_m - start_m).norm();
  if (length <= 0.0) return goal_m;
  const double s = std::clamp(speed_mps * (t_s - t0_s), 0.0, length);
  return start_m + (s / length) * (goal_m - start_m);
}

Eigen::Vector2d StraightTrajectory::Velocity(double t_s) const {
  const double length = (goal_m - start_m).norm();
  const double s = speed_mps * (t_s - t0_s);
  if (length <= 0.0 || s < 0.0 || s >= length) return Eigen::Vector2d::Zero();
  return (speed_mps / length) * (goal_m - start_m);
}

// Martins et al. 2008, Eq. 4 (kinematic controller), with v clamped at 0 so the robot never
// drives backwards into what its laser has not seen; it turns on the spot instead.
Control TrackReference(const Pose2& pose, const Eigen::Vector2d& reference_m,
                       const Eigen::Vector2d& reference_velocity_mps,
                       const TrajectoryControlParams& params) {
  const double a = params.point_ahead_m;
  const double c = std::cos(pose.theta());
  const double s = std::sin(pose.theta());
  const Eigen::Vector2d h = pose.translation() + a * Eigen::Vector2d(c, s);
  const double l = params.saturation_m;
  const Eigen::Vector2d e = reference_m - h;
  const Eigen::Vector2d nu =
      reference_velocity_mps +
      Eigen::Vector2d(l * std::tanh(params.gain_per_s * e.x() / l),
                      l * std::tanh(params.gain_per_s * e.y() / l));
  Control u(2);
  u(0) = std::clamp(c * nu.x() + s * nu.y(), 0.0, params.max_speed_mps);
  u(1) = std::clamp((-s * nu.x() + c * nu.y()) / a, -params.max_turn_rate_radps,
                    params.max_turn_rate_radps);
  return u;
}

namespace {

// The nearest return of `scan` (robot frame) in the corridor of half width `half_width_m` along
// `goal` (robot frame), at most `within_m` ahead along it and not beyond the goal.
std::optional<Eigen::Vector2d> NearestInTheWay(const LaserScan& scan, const Eigen::Vector2d& goal,
                                               double within_m, double half_width_m) {
  const double length = goal.norm();
  if (length <= 0.0) return std::nullopt;
  const Eigen::Vector2d along = goal / length;
  const double reach = std::min(within_m, length);
  std::optional<Eigen::Vector2d> obstacle;
  for (int i = 0; i < static_cast<int>(scan.ranges_m.size()); ++i) {
    if (!scan.IsReturn(i)) continue;
    const double a = scan.BeamAngle(i);
    const Eigen::Vector2d p = scan.laser_offset.TransformFrom(
        scan.ranges_m[i] * Eigen::Vector2d(std::cos(a), std::sin(a)));
    const double s = p.dot(along);
    const double lateral = std::abs(along.x() * p.y() - along.y() * p.x());
    if (s <= 0.0 || s > reach || lateral > half_width_m) continue;
    if (!obstacle || p.norm() < obstacle->norm()) obstacle = p;
  }
  return obstacle;
}

}  // namespace

// Brandão et al. 2008: the nearest return, if close and in the way, sets the direction to its
// tangent; the side is chosen once per goal, toward it.
std::optional<Eigen::Vector2d> TangentialEscape::Direction(const Pose2& pose,
                                                           const Eigen::Vector2d& goal_m,
                                                           const LaserScan& scan) {
  const double reach = active() ? params_.release_distance_m : params_.trigger_distance_m;
  const Eigen::Vector2d goal = pose.TransformTo(goal_m);
  const std::optional<Eigen::Vector2d> obstacle =
      NearestInTheWay(scan, goal, reach, params_.corridor_half_width_m);
  active_ = obstacle.has_value();
  if (!active_) return std::nullopt;
  const double bearing = std::atan2(obstacle->y(), obstacle->x());
  const double beta = WrapAngle(bearing - std::atan2(goal.y(), goal.x()));
  // An obstacle left of the goal's direction (β > 0) is passed on its right, and vice versa.
  if (side_ == 0.0) side_ = beta >= 0.0 ? -1.0 : 1.0;
  const double heading = pose.theta() + bearing + side_ * M_PI / 2.0;
  return Eigen::Vector2d(std::cos(heading), std::sin(heading));
}

}  // namespace slamkit
