#include "slamkit/planning/grid_explorer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

// The point of leg `leg` (from w[leg] to w[leg + 1]) nearest to p, as its distance along the leg.
double ProjectOnLeg(const std::vector<Eigen::Vector2d>& w, std::size_t leg,
                    const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = w[leg + 1] - w[leg];
  const double length = d.norm();
  if (length <= 0.0) return 0.0;
  return std::clamp((p - w[leg]).dot(d) / length, 0.0, length);
}

// The leg nearest to p among those starting at most horizon_m of path after leg `from`: the
// robot moves on along the path, and a later stretch passing close by (a path around a block)
// must not pull it ahead.
std::size_t NearestLeg(const std::vector<Eigen::Vector2d>& w, std::size_t from,
                       const Eigen::Vector2d& p, double horizon_m) {
  std::size_t best = from;
  double best_d = std::numeric_limits<double>::infinity();
  double arc = 0.0;
  for (std::size_t leg = from; leg + 1 < w.size() && arc <= horizon_m; ++leg) {
    const Eigen::Vector2d d = w[leg + 1] - w[leg];
    const double s = ProjectOnLeg(w, leg, p);
    const double dist = (w[leg] + (d.norm() > 0.0 ? s / d.norm() : 0.0) * d - p).norm();
    if (dist < best_d) best_d = dist, best = leg;
    arc += d.norm();
  }
  return best;
}

// The point `ahead_m` along the path from distance s on leg `leg`, and the unit direction there
// (zero at the path's end, where the robot should stop).
std::pair<Eigen::Vector2d, Eigen::Vector2d> PointAhead(const std::vector<Eigen::Vector2d>& w,
                                                       std::size_t leg, double s, double ahead_m) {
  double left = s + ahead_m;
  for (; leg + 1 < w.size(); ++leg) {
    const Eigen::Vector2d d = w[leg + 1] - w[leg];
    const double length = d.norm();
    if (length > 0.0 && left < length) return {w[leg] + (left / length) * d, d / length};
    left -= length;
  }
  return {w.back(), Eigen::Vector2d::Zero()};
}

// The distance from p to the nearest point of a cell the planner counts as an obstacle (known,
// above occupied_probability), or reach_m when none is nearer.
double ObstacleDistance(const OccupancyGrid& map, const Eigen::Vector2d& p, double reach_m,
                        double occupied_probability) {
  const double r = map.resolution();
  const CellIndex c = map.WorldToCell(p);
  const int k = static_cast<int>(std::ceil(reach_m / r));
  double best = reach_m;
  for (int dy = -k; dy <= k; ++dy) {
    for (int dx = -k; dx <= k; ++dx) {
      const CellIndex q{c.x + dx, c.y + dy};
      if (!map.IsKnown(q) || map.Probability(q) <= occupied_probability) continue;
      const Eigen::Vector2d centre = map.CellCenter(q);
      const double ex = std::max(std::abs(p.x() - centre.x()) - 0.5 * r, 0.0);
      const double ey = std::max(std::abs(p.y() - centre.y()) - 0.5 * r, 0.0);
      best = std::min(best, std::hypot(ex, ey));
    }
  }
  return best;
}

// Whether every point of the segment from a to b (sampled every half cell) keeps at least min_m
// from the obstacles.
bool SegmentKeeps(const OccupancyGrid& map, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                  double min_m, double occupied_probability) {
  const double step = 0.5 * map.resolution();
  const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
  for (int i = 1; i <= n; ++i) {
    const Eigen::Vector2d q = a + (static_cast<double>(i) / n) * (b - a);
    if (ObstacleDistance(map, q, min_m, occupied_probability) < min_m) return false;
  }
  return true;
}

}  // namespace

GridExplorer::GridExplorer(const GridExplorerParams& params) : params_(params) {}

// SPEC S4: the explorer driven by the SLAM estimate. Plan when due, turn once at the start, then
// follow the path to the nearest reachable frontier.
Control GridExplorer::Step(const Pose2& estimate, const OccupancyGrid& map, double t_s,
                           const FrontierSkip& skip) {
  target_changed_ = false;
  RecordReachedGoal(estimate, map);
  if (NeedsPlan(map, t_s)) Plan(estimate, map, t_s, skip);
  Control u = Control::Zero(2);
  if (!target_) return u;
  if (!start_turn_done_) {
    if (TurnAtStart(estimate, &u)) return u;
    Plan(estimate, map, t_s, skip);  // the map now holds the whole surroundings of the start
    if (!target_) return u;
  }
  return Follow(estimate, map);
}

// A goal reached is given up whatever the map says, and its surroundings with it (see the class).
void GridExplorer::RecordReachedGoal(const Pose2& estimate, const OccupancyGrid& map) {
  if (!target_ || !start_turn_done_) return;
  const Eigen::Vector2d goal = map.CellCenter(target_->cell);
  if ((goal - estimate.translation()).norm() >= params_.goal_reach_m) return;
  reached_m_.push_back(goal);
  target_.reset();
  last_plan_s_.reset();
}

bool GridExplorer::NeedsPlan(const OccupancyGrid& map, double t_s) const {
  if (!last_plan_s_ || t_s - *last_plan_s_ >= params_.replan_period_s) return true;
  return target_ && !IsFrontierCell(map, target_->cell, params_.frontiers);
}

void GridExplorer::Plan(const Pose2& estimate, const OccupancyGrid& map, double t_s,
                        const FrontierSkip& skip) {
  last_plan_s_ = t_s;
  std::vector<int> original;
  const std::vector<FrontierRegion> candidates =
      Candidates(map, FindFrontierRegions(map, params_.frontiers), skip, &original);
  const GridPathCosts costs = GridPathCosts::From(map, estimate.translation(), params_.paths);
  std::optional<FrontierTarget> best = NearestReachableFrontier(costs, candidates);
  done_ = !best;
  if (!best) {
    target_.reset();
    return;
  }
  if (target_) KeepCurrentGoal(costs, candidates, &*best);
  best->region = original[best->region];
  const bool changed = !target_ || !(target_->cell == best->cell);
  target_ = std::move(best);
  progress_ = 0;
  started_ = true;
  if (changed) target_changed_ = true, ++targets_chosen_;
}

// The regions `skip` keeps, without the cells near a reached goal (empty regions dropped);
// `original_index` maps each back to its place in `regions`.
std::vector<FrontierRegion> GridExplorer::Candidates(const OccupancyGrid& map,
                                                     const std::vector<FrontierRegion>& regions,
                                                     const FrontierSkip& skip,
                                                     std::vector<int>* original_index) const {
  std::vector<FrontierRegion> kept;
  for (int i = 0; i < static_cast<int>(regions.size()); ++i) {
    if (skip && skip(regions[i])) continue;
    FrontierRegion region = regions[i];
    std::erase_if(region.cells, [&](const CellIndex& c) {
      return std::any_of(reached_m_.begin(), reached_m_.end(), [&](const Eigen::Vector2d& g) {
        return (map.CellCenter(c) - g).norm() < params_.goal_reach_m;
      });
    });
    if (region.cells.empty()) continue;
    kept.push_back(std::move(region));
    original_index->push_back(i);
  }
  return kept;
}

// The current goal stays if it is still a candidate and not switch_margin_m dearer than `best`.
void GridExplorer::KeepCurrentGoal(const GridPathCosts& costs,
                                   const std::vector<FrontierRegion>& candidates,
                                   FrontierTarget* best) const {
  const CellIndex goal = target_->cell;
  const double cost = costs.Cost(goal);
  if (goal == best->cell || !(cost <= best->cost_m + params_.switch_margin_m)) return;
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    const std::vector<CellIndex>& cells = candidates[i].cells;
    if (std::find(cells.begin(), cells.end(), goal) == cells.end()) continue;
    *best = {i, goal, cost, SimplifyPath(costs, costs.PathTo(goal))};
    return;
  }
}

// A full turn at the top turn rate, measured on the estimate's heading.
bool GridExplorer::TurnAtStart(const Pose2& estimate, Control* u) {
  if (last_theta_) turned_rad_ += std::abs(WrapAngle(estimate.theta() - *last_theta_));
  last_theta_ = estimate.theta();
  if (turned_rad_ >= 2.0 * M_PI) {
    start_turn_done_ = true;
    return false;
  }
  (*u)(1) = params_.control.max_turn_rate_radps;
  return true;
}

// Pure pursuit of a point up to lookahead_m ahead of the robot's place on the path
// (ClearPointAhead), through the point-ahead controller; a large heading error is turned away on
// the spot first, since v >= 0 and a wide arc would leave the inflated path.
Control GridExplorer::Follow(const Pose2& estimate, const OccupancyGrid& map) {
  const std::vector<Eigen::Vector2d>& w = target_->waypoints_m;
  const Eigen::Vector2d p = estimate.translation();
  Eigen::Vector2d reference = w.back(), direction = Eigen::Vector2d::Zero();
  if (w.size() >= 2) {
    progress_ = NearestLeg(w, std::min(progress_, w.size() - 2), p, params_.lookahead_m + 1.0);
    std::tie(reference, direction) =
        ClearPointAhead(map, w, progress_, ProjectOnLeg(w, progress_, p), p);
  }
  const Eigen::Vector2d to_reference = reference - p;
  const double error =
      WrapAngle(std::atan2(to_reference.y(), to_reference.x()) - estimate.theta());
  if (std::abs(error) > params_.turn_in_place_rad) {
    Control u = Control::Zero(2);
    u(1) = std::copysign(params_.control.max_turn_rate_radps, error);
    return u;
  }
  return TrackReference(estimate, reference, params_.control.speed_mps * direction,
                        params_.control);
}

// The pursuit's point: lookahead_m ahead on the path, or nearer (three quarters, a half, a
// quarter of it, then the path's point nearest the robot) until the straight line to it keeps
// the robot's radius from every obstacle, or keeps what the robot has when it is already nearer.
// Past a door jamb the full look-ahead would steer the robot across the jamb's inflated zone
// (docs/pslam.md, "Open").
std::pair<Eigen::Vector2d, Eigen::Vector2d> GridExplorer::ClearPointAhead(
    const OccupancyGrid& map, const std::vector<Eigen::Vector2d>& waypoints, std::size_t leg,
    double s, const Eigen::Vector2d& position) const {
  const double occupied = params_.paths.occupied_probability;
  const double radius = params_.paths.robot_radius_m;
  const double keep = std::min(radius, ObstacleDistance(map, position, radius, occupied));
  for (int quarters = 4; quarters > 0; --quarters) {
    const auto point = PointAhead(waypoints, leg, s, params_.lookahead_m * quarters / 4.0);
    if (SegmentKeeps(map, position, point.first, keep, occupied)) return point;
  }
  return PointAhead(waypoints, leg, s, 0.0);
}

}  // namespace slamkit
