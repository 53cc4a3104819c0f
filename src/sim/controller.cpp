#include "slamkit/sim/controller.hpp"

#include <algorithm>
#include <cmath>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

// The route is closed: waypoints 0 … n−1, then waypoint 0 again. Reaching the last waypoint
// completes a loop; reaching waypoint 0 after `loops` loops ends the run (returns true).
bool AdvanceRoute(const RouteParams& route, const Pose2& true_pose, int* current, int* loop) {
  const Eigen::Vector2d& target = route.waypoints_m[*current];
  if ((target - true_pose.translation()).norm() > route.switch_distance_m) return false;
  if (*current == 0 && *loop >= route.loops) return true;
  ++*current;
  if (*current == static_cast<int>(route.waypoints_m.size())) {
    *current = 0;
    ++*loop;
  }
  return false;
}

}  // namespace

WaypointController::WaypointController(const RouteParams& route, const ControllerParams& params,
                                       MotionKind kind)
    : route_(route), params_(params), kind_(kind) {
  done_ = route_.waypoints_m.empty();
}

Control WaypointController::Command(const Pose2& true_pose, double dt_s) {
  if (detour_m_ &&
      (*detour_m_ - true_pose.translation()).norm() <= route_.switch_distance_m) {
    detour_m_.reset();
  }
  // On a detour the route waits at its current waypoint, so it resumes there.
  if (!done_ && !detour_m_) done_ = AdvanceRoute(route_, true_pose, &current_, &loop_);
  if (done_) {
    Control u(2);
    u << 0.0, kind_ == MotionKind::kCarLike ? steer_rad_ : 0.0;
    return u;
  }
  return Steer(detour_m_ ? *detour_m_ : route_.waypoints_m[current_], true_pose, dt_s);
}

Control WaypointController::Steer(const Eigen::Vector2d& target_m, const Pose2& true_pose,
                                  double dt_s) {
  Control u(2);
  const Eigen::Vector2d to_target = target_m - true_pose.translation();
  const double bearing_rad = std::atan2(to_target.y(), to_target.x());
  if (kind_ == MotionKind::kCarLike) {
    // The car moves along θ + G (SPEC S2, Eq. 2): steer that direction at the waypoint.
    const double max_change = params_.max_steer_rate_radps * dt_s;
    const double change = std::clamp(WrapAngle(bearing_rad - true_pose.theta() - steer_rad_),
                                     -max_change, max_change);
    steer_rad_ = std::clamp(steer_rad_ + change, -params_.max_steer_rad, params_.max_steer_rad);
    u << params_.speed_mps, steer_rad_;
  } else {
    const double error_rad = WrapAngle(bearing_rad - true_pose.theta());
    const double omega = std::clamp(params_.heading_gain_per_s * error_rad,
                                    -params_.max_turn_rate_radps, params_.max_turn_rate_radps);
    u << params_.speed_mps, omega;
  }
  return u;
}

}  // namespace slamkit
