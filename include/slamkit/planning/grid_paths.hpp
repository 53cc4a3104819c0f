#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
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
  // Dijkstra stopped once every cell as cheap as the cheapest cell with is_goal(cell) is
  // settled: Cost is exact up to that cost and +inf or an upper bound above it. Without a
  // reachable goal the search runs to the end, as From. goal() is the first goal settled.
  static GridPathCosts UpToNearestGoal(const OccupancyGrid& grid, const Eigen::Vector2d& start_m,
                                       const std::function<bool(const CellIndex&)>& is_goal,
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
  const std::optional<CellIndex>& goal() const { return goal_; }
  // A clearance is a rounded product (resolution × a distance in cells): one that is exactly the
  // radius (the middle of a gap 2 × radius + one cell wide) may come out this much below it,
  // and must not block.
  static constexpr double kClearanceSlack_m = 1e-9;
  double resolution() const { return resolution_m_; }
  const GridPathParams& params() const { return params_; }

 private:
  // The window is stored in tiles prepared (free cells and clearance read from the grid) when
  // the search first reaches them: a map's written window is mostly unknown (beams with no
  // return write free cells tens of metres out), and the search only touches what is reachable.
  static constexpr int kTileBits = 6;
  static constexpr int kTileSize = 1 << kTileBits;
  static constexpr int kTileCells = kTileSize * kTileSize;
  struct Tile {
    std::array<char, kTileCells> free;
    std::array<double, kTileCells> clearance_m;
    std::array<double, kTileCells> cost_m;
    std::array<std::int8_t, kTileCells> parent;  // the step (index into the 8 neighbours)
  };

  GridPathCosts(const OccupancyGrid& grid, const Eigen::Vector2d& start_m,
                const GridPathParams& params);
  bool Contains(const CellIndex& c) const {
    return c.x >= x0_ && c.y >= y0_ && c.x < x0_ + width_ && c.y < y0_ + height_;
  }
  std::size_t TileIndex(const CellIndex& c) const {
    return static_cast<std::size_t>((c.y - y0_) >> kTileBits) * static_cast<std::size_t>(tiles_x_) +
           static_cast<std::size_t>((c.x - x0_) >> kTileBits);
  }
  static int InTile(const CellIndex& c, const CellIndex& origin) {
    return ((c.y - origin.y) & (kTileSize - 1)) * kTileSize + ((c.x - origin.x) & (kTileSize - 1));
  }
  int InTile(const CellIndex& c) const { return InTile(c, {x0_, y0_}); }
  const Tile* FindTile(const CellIndex& c) const;  // nullptr outside or not prepared yet
  Tile& PreparedTile(const CellIndex& c);
  void PrepareClearance(const CellIndex& tile_origin, Tile& tile) const;
  bool ReadFree(const CellIndex& c) const;
  bool ReadOccupied(const CellIndex& c) const;
  bool OnObstacleBorder(const CellIndex& c) const;
  double ReadClearance(const CellIndex& c) const;  // for a cell of a tile not prepared
  void RunDijkstra(const std::function<bool(const CellIndex&)>& is_goal);

  OccupancyGrid grid_;  // a copy sharing the tiles, read as the search reaches them
  GridPathParams params_;
  double resolution_m_ = 0.0;
  CellIndex start_;
  std::optional<CellIndex> goal_;
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;  // the window
  int tiles_x_ = 0;
  int reach_cells_ = 0;  // the disc's half-width in cells
  struct DiscOffset { int dx, dy; double d_m; };
  std::vector<DiscOffset> disc_;  // offsets within robot_radius_m + clearance_m, nearest first
  std::vector<std::shared_ptr<Tile>> tiles_;
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
