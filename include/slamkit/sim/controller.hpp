#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/models/vehicle.hpp"

namespace slamkit {

// A closed route of waypoints driven `loops` times.
struct RouteParams {
  std::vector<Eigen::Vector2d> waypoints_m;
  int loops = 1;
  double switch_distance_m = 1.0;  // a waypoint is reached within this distance
};

struct ControllerParams {
  double speed_mps = 3.0;
  // Car-like: steering angle limit and steering rate limit.
  double max_steer_rad = 0.5236;        // 30°
  double max_steer_rate_radps = 0.3491; // 20°/s
  // Unicycle and odometry: turn-rate limit and proportional gain on the heading error.
  double max_turn_rate_radps = 1.0;
  double heading_gain_per_s = 2.0;
};

// Drives the true vehicle along the route: steers toward the current waypoint within the rate and
// angle limits, and advances to the next waypoint once it is within switch distance.
// A detour (SWSLAM's self-detected waypoint, SPEC S2) is driven to before the route goes on: the
// route stays at its current waypoint meanwhile (waypoints passed on the way do not count), and
// the detour ends itself once reached within switch distance.
class WaypointController {
 public:
  WaypointController(const RouteParams& route, const ControllerParams& params, MotionKind kind);

  // The command for the next step from the true pose: (v, G) for car-like, (v, ω) otherwise.
  Control Command(const Pose2& true_pose, double dt_s);
  bool Done() const { return done_; }
  int CurrentWaypoint() const { return current_; }

  // Sets (or, with nullopt, abandons) the detour; it replaces any detour not yet reached.
  void SetDetour(const std::optional<Eigen::Vector2d>& point_m) { detour_m_ = point_m; }
  const std::optional<Eigen::Vector2d>& Detour() const { return detour_m_; }

 private:
  Control Steer(const Eigen::Vector2d& target_m, const Pose2& true_pose, double dt_s);

  RouteParams route_;
  ControllerParams params_;
  MotionKind kind_;
  int current_ = 0;
  int loop_ = 0;
  bool done_ = false;
  double steer_rad_ = 0.0;  // car-like: the present steering angle
  std::optional<Eigen::Vector2d> detour_m_;
};

}  // namespace slamkit
