#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/planning/grid_frontiers.hpp"

namespace slamkit {

// Path costs on an inflated occupancy grid, for the next exploration target (SPEC S4, step 1:
// the nearest reachable frontier by path cost).
struct GridPathParams {
  // A cell whose centre is closer than this to an occupied cell (to the nearest point of its
  // square) is blocked: the inflation. A gap narrower than 2 × robot_radius_m between obstacle
  // cells blocks; one at least 2 × robot_radius_m + one cell wide always passes.
  double robot_radius_m = 0.3;
  // Cells less than robot_radius_m + clearance_m from an obstacle cost extra, so that paths keep
  // to the middle of corridors instead of grazing the inflation.
  double clearance_m = 0.4;
  // The extra cost per metre of path at robot_radius_m, falling linearly to 0 at
  // robot_radius_m + clearance_m (a metre at the radius costs 1 + weight).
  double clearance_cost_weight = 2.0;
  // A known cell below this occupancy is traversable; unknown and uncertain cells are not.
  double free_probability = 0.35;
  // A known cell above this occupancy is an obstacle to inflate.
  double occupied_probability = 0.65;
};

// Dijkstra path costs in metres (8-connected: a step costs its length times 1 + the clearance
// penalty, the mean of its two cells') from one start cell over the grid's written cells and a
// ring of one around them.
// A start inside an inflated zone (the estimate drifted near a wall): the path may leave it
// through blocked free cells, each step strictly farther from the obstacles than the last, at the
// full penalty; it can never move along or toward a wall inside the zone. The start cell itself is
// the source whatever it holds (unknown before the first scan, occupied after an estimate error).
class GridPathCosts {
 public:
  // Throws std::invalid_argument for negative distances or weight, or probabilities not in
  // 0 < free <= occupied < 1.
  static GridPathCosts From(const OccupancyGrid& grid, const Eigen::Vector2d& start_m,
                            const GridPathParams& params = {});

  bool Reachable(const CellIndex& c) const;
  double Cost(const CellIndex& c) const;  // metres with penalties, +inf when unreachable
  // The cells from the start to `goal` (both included), empty when unreachable.
  std::vector<CellIndex> PathTo(const CellIndex& goal) const;

  // The distance from the cell's centre to the nearest occupied cell, +inf when none lies within
  // robot_radius_m + clearance_m (the field is only computed that far).
  double Clearance(const CellIndex& c) const;
  bool IsFree(const CellIndex& c) const;       // known and below free_probability
  bool Traversable(const CellIndex& c) const;  // free and not inflated
  CellIndex start() const { return start_; }
  double resolution() const { return resolution_m_; }
  const GridPathParams& params() const { return params_; }

 private:
  GridPathCosts() = default;
  bool Contains(const CellIndex& c) const {
    return c.x >= x0_ && c.y >= y0_ && c.x < x0_ + width_ && c.y < y0_ + height_;
  }
  std::size_t Index(const CellIndex& c) const {
    return static_cast<std::size_t>(c.y - y0_) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(c.x - x0_);
  }
  void ComputeClearance(const OccupancyGrid& grid);
  void RunDijkstra();

  GridPathParams params_;
  double resolution_m_ = 0.0;
  CellIndex start_;
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;  // the window
  std::vector<char> free_;
  std::vector<double> clearance_m_;
  std::vector<double> cost_m_;
  std::vector<std::int8_t> parent_;  // the step (index into the 8 neighbours) that reached a cell
};

// The path's cells as waypoints in metres (their centres): the first and last, and a point where
// a straight line would no longer do. A shortcut is taken only when every cell under it is free
// and at least as far from the obstacles as the path it replaces was (never less than the robot
// radius, never more than radius + clearance needed), so the line keeps the path's clearance and
// the cells of an escape from an inflated start stay as they are. No leg is longer than
// max_segment_m, so a follower or a display sees the path's shape as it goes.
std::vector<Eigen::Vector2d> SimplifyPath(const GridPathCosts& costs,
                                          const std::vector<CellIndex>& path,
                                          double max_segment_m = 2.0);

struct FrontierTarget {
  int region = -1;  // index into the regions given
  CellIndex cell;
  double cost_m = 0.0;
  std::vector<Eigen::Vector2d> waypoints_m;  // SimplifyPath of the path from the start
};

using FrontierSkip = std::function<bool(const FrontierRegion&)>;

// SPEC S4, step 1: the frontier cell with the least path cost over the regions for which
// skip(region) is false (an empty skip skips none); ties go to the earlier region and cell. None
// when no frontier cell is reachable. A frontier cell is a goal like any free cell: one inside an
// inflated zone (a frontier along a wall, in a corridor narrower than 2 × robot_radius_m) is
// unreachable.
std::optional<FrontierTarget> NearestReachableFrontier(const OccupancyGrid& grid,
                                                       const std::vector<FrontierRegion>& regions,
                                                       const Eigen::Vector2d& start_m,
                                                       const GridPathParams& params = {},
                                                       const FrontierSkip& skip = {});
// The same on costs computed already (the explorer compares its current goal on the same ones).
std::optional<FrontierTarget> NearestReachableFrontier(const GridPathCosts& costs,
                                                       const std::vector<FrontierRegion>& regions,
                                                       const FrontierSkip& skip = {});

}  // namespace slamkit
