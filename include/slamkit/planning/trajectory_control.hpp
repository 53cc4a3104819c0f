#pragma once

#include <optional>

#include <Eigen/Core>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/models/motion_model.hpp"

namespace slamkit {

// The unicycle trajectory controller of the active loop (SPEC S1). The seed uses the adaptive
// dynamic controller of De la Cruz et al. 2008; its kinematic part is the point-ahead
// linearisation of Martins et al. 2008, which is what a simulated unicycle needs: a point `a`
// ahead of the wheel axis, h = p + a (cos θ, sin θ), follows the reference through
//   [v ω]ᵀ = A(θ)⁻¹ (ḣ_d + l tanh(K (h_d − h) / l)),   A(θ) = [cos θ  −a sin θ; sin θ  a cos θ].
struct TrajectoryControlParams {
  double speed_mps = 0.3;          // along the straight trajectory
  double point_ahead_m = 0.2;      // a
  double gain_per_s = 0.8;         // K
  double saturation_m = 0.3;       // l: the position error's share of the command is bounded
  double max_speed_mps = 0.5;      // v is clamped to [0, max]: the laser looks forward
  double max_turn_rate_radps = 1.0;
};

// A straight trajectory from `start_m` to `goal_m` at constant speed, started at t0_s; it stays
// at the goal once there.
struct StraightTrajectory {
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d goal_m = Eigen::Vector2d::Zero();
  double speed_mps = 0.3;
  double t0_s = 0.0;

  Eigen::Vector2d Position(double t_s) const;
  Eigen::Vector2d Velocity(double t_s) const;
};

// The command (v, ω) that steers the point ahead of `pose` onto the reference position and
// velocity (world frame).
Control TrackReference(const Pose2& pose, const Eigen::Vector2d& reference_m,
                       const Eigen::Vector2d& reference_velocity_mps,
                       const TrajectoryControlParams& params = {});

// Tangential escape (Brandão et al. 2008), the avoidance of the active loop: when a return lies
// in the way (within corridor_half_width_m of the straight line to the goal, nearer than
// trigger_distance_m along it), the robot heads along that obstacle's tangent, on the side chosen
// at the first escape toward this goal, and resumes the goal once nothing is in the way within
// release_distance_m. The two distances and the kept side are the hysteresis without which the
// robot would switch between the goal and the tangent, or between the two sides, every period.
struct AvoidanceParams {
  double trigger_distance_m = 0.8;
  double release_distance_m = 1.1;
  double corridor_half_width_m = 0.35;  // the robot's half width and a margin
};

class TangentialEscape {
 public:
  explicit TangentialEscape(const AvoidanceParams& params = {}) : params_(params) {}

  // The direction to head for (a unit vector, world frame) instead of the goal's, or none when no
  // obstacle is in the way. `scan` is the latest scan at `pose`.
  std::optional<Eigen::Vector2d> Direction(const Pose2& pose, const Eigen::Vector2d& goal_m,
                                           const LaserScan& scan);
  bool active() const { return active_; }
  // A new goal: the next escape chooses its side again.
  void Reset() { active_ = false, side_ = 0.0; }

 private:
  AvoidanceParams params_;
  bool active_ = false;
  double side_ = 0.0;  // the tangent's turn from the obstacle's bearing (±1), 0 until chosen
};

}  // namespace slamkit
