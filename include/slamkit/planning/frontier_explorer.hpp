#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/planning/frontiers.hpp"
#include "slamkit/planning/trajectory_control.hpp"

namespace slamkit {

struct FrontierExplorerParams {
  FrontierParams frontiers;
  FrontierChoiceParams choice;
  TrajectoryControlParams control;
  AvoidanceParams avoidance;
  double reach_radius_m = 0.5;      // a goal is reached this close
  double goal_timeout_s = 60.0;     // a goal not reached by then is given up (and not retried)
  double turn_rate_radps = 0.5;     // turning in place when no frontier is seen
  // The path is kept as a point every this far: the way back follows it, close to where the
  // robot actually drove (around obstacles, through doors).
  double breadcrumb_spacing_m = 0.5;
};

enum class ExplorerMode {
  kTracking,  // following the straight trajectory to the goal
  kAvoiding,  // tangential escape around an obstacle, goal kept
  kTurning,   // no frontier in sight: turning in place
  kReturning, // back along the visited goals to where an unvisited frontier was seen
  kDone,      // a whole turn found no frontier, and none seen before is left
};

// The active loop of SPEC S1 (seed section 3.1) as a controller: each control period it takes
// the SLAM pose estimate and the latest scan and returns the unicycle command (v, ω). It never
// sees the true pose; whoever drives the robot decides what estimate to give it.
// The seed stops at "turn until a frontier appears", which leaves a robot in a room whose walls
// are all in range turning for ever. Here every frontier seen on the way and not chosen is kept
// (one per revisit radius), and after a whole turn without one the robot drives back along its
// path (breadcrumbs where it drove, so free) to where the latest still-unvisited one was seen
// and goes there: a depth-first exploration that ends when no frontier is left.
class FrontierExplorer {
 public:
  explicit FrontierExplorer(const FrontierExplorerParams& params = {});

  // The command for the control period starting at t_s (non-decreasing across calls).
  Control Step(const Pose2& estimate, const LaserScan& scan, double t_s);

  ExplorerMode mode() const { return mode_; }
  std::optional<Eigen::Vector2d> goal() const { return goal_; }
  // The start and every goal reached or given up, in order.
  const std::vector<Eigen::Vector2d>& visited() const { return visited_; }

 private:
  struct Pending {
    Eigen::Vector2d point_m;
    std::size_t depth = 0;  // path_.size() when it was seen: path_.back() was where
  };
  void FinishGoalIfDone(const Pose2& estimate, double t_s);
  void ChooseGoal(const Pose2& estimate, const std::vector<Frontier>& frontiers, double t_s);
  void KeepForLater(const std::vector<Frontier>& frontiers);
  void SetGoal(const Eigen::Vector2d& goal, const Pose2& estimate, double t_s);
  bool ReturnToPending(const Pose2& estimate, double t_s);
  Control TurnInPlace(const Pose2& estimate, double t_s);
  Control Drive(const Pose2& estimate, const LaserScan& scan, double t_s);

  FrontierExplorerParams params_;
  ExplorerMode mode_ = ExplorerMode::kTurning;
  std::optional<Eigen::Vector2d> goal_;
  StraightTrajectory trajectory_;
  TangentialEscape escape_;
  bool escaping_ = false;  // the last period escaped an obstacle
  double goal_started_s_ = 0.0;
  std::vector<Eigen::Vector2d> visited_;
  std::vector<Eigen::Vector2d> path_;  // breadcrumbs from the start to the robot (the DFS branch)
  std::vector<Pending> pending_;
  std::vector<Eigen::Vector2d> route_;  // the goals after the current one, last first
  std::optional<double> last_t_s_;
  double turned_rad_ = 0.0;  // in place since the last goal
};

}  // namespace slamkit
