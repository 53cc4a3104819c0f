#pragma once

#include <cstddef>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/planning/grid_frontiers.hpp"
#include "slamkit/planning/grid_paths.hpp"
#include "slamkit/planning/trajectory_control.hpp"

namespace slamkit {

struct GridExplorerParams {
  GridFrontierParams frontiers;
  GridPathParams paths;
  // The seed's robot: 0.2 m/s top speed, turning at most 1 rad/s.
  TrajectoryControlParams control = {.speed_mps = 0.2, .point_ahead_m = 0.2, .gain_per_s = 0.8,
                                     .saturation_m = 0.3, .max_speed_mps = 0.2,
                                     .max_turn_rate_radps = 1.0};
  // The path is recomputed this often (the map grows under it), and at once when the goal is
  // reached or is no longer a frontier cell.
  double replan_period_s = 3.0;
  // A replanned goal is kept unless another frontier is cheaper by this much: the nearest cell
  // of a frontier moves as the robot does, and the goal would otherwise hop along it (each hop
  // is a new target, for which a P-SLAM runner starts a prediction).
  double switch_margin_m = 1.0;
  double lookahead_m = 0.5;       // the point on the path the robot steers to
  double goal_reach_m = 0.3;      // the goal is reached this close
  double turn_in_place_rad = 1.0; // a heading error above this turns in place (v = 0) first
};

// Frontier exploration on the SLAM map (SPEC S4: the explorer of the simulated laser robot).
// Each control period it takes the SLAM pose estimate and map (e.g. the best particle's) and
// returns the unicycle command (v, ω); it never sees the truth. It drives to the nearest
// reachable frontier (NearestReachableFrontier on the inflated map) along the simplified path,
// steering to a point lookahead_m ahead on it with TrackReference (nearer where the straight line
// to that point would bring the robot within its radius of an obstacle), and stops when no reachable
// frontier is left that `skip` keeps (P-SLAM: regions already predicted need no visit).
// Once there is something to explore, it first turns a full 2π in place: the laser sees 180°
// only, and the map behind the start would otherwise be unknown until the robot came back.
// A goal reached that is still a frontier (its unknown side cannot be seen from there) is not
// chosen again: frontier cells within goal_reach_m of a reached goal are left out from then on.
// done() is the last plan's answer, not a latch: while done, the plan is retried every
// replan_period_s, so a region whose prediction is later dropped (skip false again) is explored.
class GridExplorer {
 public:
  explicit GridExplorer(const GridExplorerParams& params = {});

  // The command for the control period starting at t_s (non-decreasing across calls). Call it
  // once the first scan is in `map`: on an empty map there is nothing to explore.
  Control Step(const Pose2& estimate, const OccupancyGrid& map, double t_s,
               const FrontierSkip& skip = {});

  bool done() const { return done_; }  // no reachable, unskipped frontier was left
  std::optional<FrontierTarget> target() const { return target_; }  // the current goal
  int targets_chosen() const { return targets_chosen_; }
  // Whether the last Step chose a new goal cell (a runner starts a prediction for it).
  bool target_changed() const { return target_changed_; }
  bool turning_at_start() const { return started_ && !start_turn_done_; }

 private:
  void RecordReachedGoal(const Pose2& estimate, const OccupancyGrid& map);
  bool NeedsPlan(const OccupancyGrid& map, double t_s) const;
  void Plan(const Pose2& estimate, const OccupancyGrid& map, double t_s, const FrontierSkip& skip);
  std::vector<FrontierRegion> Candidates(const OccupancyGrid& map,
                                         const std::vector<FrontierRegion>& regions,
                                         const FrontierSkip& skip,
                                         std::vector<int>* original_index) const;
  void KeepCurrentGoal(const GridPathCosts& costs, const std::vector<FrontierRegion>& candidates,
                       FrontierTarget* best) const;
  bool TurnAtStart(const Pose2& estimate, Control* u);
  Control Follow(const Pose2& estimate, const OccupancyGrid& map);
  std::pair<Eigen::Vector2d, Eigen::Vector2d> ClearPointAhead(
      const OccupancyGrid& map, const std::vector<Eigen::Vector2d>& waypoints, std::size_t leg,
      double s, const Eigen::Vector2d& position) const;

  GridExplorerParams params_;
  std::optional<FrontierTarget> target_;
  bool done_ = false;
  bool target_changed_ = false;
  int targets_chosen_ = 0;
  std::optional<double> last_plan_s_;
  bool started_ = false;          // a plan found something to explore
  bool start_turn_done_ = false;
  double turned_rad_ = 0.0;
  std::optional<double> last_theta_;
  std::size_t progress_ = 0;      // the path leg the robot was last nearest to
  std::vector<Eigen::Vector2d> reached_m_;  // goals reached that stayed frontiers
};

}  // namespace slamkit
