#include "slamkit/planning/grid_paths.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <unordered_set>

namespace slamkit {
namespace {

std::uint64_t CellKey(const CellIndex& c) {
  return (std::uint64_t{static_cast<std::uint32_t>(c.y)} << 32) | static_cast<std::uint32_t>(c.x);
}

}  // namespace

// Greedy line-of-sight: from the last waypoint, the path is followed as long as the straight line
// to its next cell keeps the clearance of the stretch it replaces (see the header).
std::vector<Eigen::Vector2d> SimplifyPath(const GridPathCosts& costs,
                                          const std::vector<CellIndex>& path,
                                          double max_segment_m) {
  if (path.empty()) return {};
  const double r = costs.params().robot_radius_m;
  const double needed_max = r + costs.params().clearance_m;
  const double res = costs.resolution();
  const auto centre = [res](const CellIndex& c) {
    return Eigen::Vector2d((c.x + 0.5) * res, (c.y + 0.5) * res);
  };
  const auto line_clear = [&](const CellIndex& a, const CellIndex& b, double needed) {
    const std::vector<CellIndex> cells = RayCells(a, b);
    return std::all_of(cells.begin() + 1, cells.end(), [&](const CellIndex& c) {
      return costs.IsFree(c) && costs.Clearance(c) >= needed - GridPathCosts::kClearanceSlack_m;
    });
  };
  std::vector<Eigen::Vector2d> waypoints = {centre(path.front())};
  std::size_t anchor = 0;
  double stretch_clearance = std::numeric_limits<double>::infinity();  // the least clearance of path(anchor, j]
  for (std::size_t j = 1; j < path.size(); ++j) {
    stretch_clearance = std::min(stretch_clearance, costs.Clearance(path[j]));
    if (j == anchor + 1) continue;  // a neighbour is always in sight
    const double needed = std::clamp(stretch_clearance, r, needed_max);
    const bool too_long = (centre(path[j]) - waypoints.back()).norm() > max_segment_m;
    if (too_long || !line_clear(path[anchor], path[j], needed)) {
      anchor = j - 1;
      waypoints.push_back(centre(path[anchor]));
      stretch_clearance = costs.Clearance(path[j]);
    }
  }
  if (path.size() > 1) waypoints.push_back(centre(path.back()));
  return waypoints;
}

std::optional<FrontierTarget> NearestReachableFrontier(const GridPathCosts& costs,
                                                       const std::vector<FrontierRegion>& regions,
                                                       const FrontierSkip& skip) {
  std::optional<FrontierTarget> best;
  for (int i = 0; i < static_cast<int>(regions.size()); ++i) {
    if (skip && skip(regions[i])) continue;
    for (const CellIndex& c : regions[i].cells) {
      const double cost = costs.Cost(c);
      if (std::isfinite(cost) && (!best || cost < best->cost_m)) best = {i, c, cost, {}};
    }
  }
  if (best) best->waypoints_m = SimplifyPath(costs, costs.PathTo(best->cell));
  return best;
}

// SPEC S4 step 1: the next exploration target.
std::optional<FrontierTarget> NearestReachableFrontier(const OccupancyGrid& grid,
                                                       const std::vector<FrontierRegion>& regions,
                                                       const Eigen::Vector2d& start_m,
                                                       const GridPathParams& params,
                                                       const FrontierSkip& skip) {
  // The search stops once the nearest goal's cost is settled: ties are then all settled too, and
  // the choice over the regions below is the one a full search gives.
  std::unordered_set<std::uint64_t> goals;
  for (const FrontierRegion& region : regions) {
    if (skip && skip(region)) continue;
    for (const CellIndex& c : region.cells) goals.insert(CellKey(c));
  }
  const auto is_goal = [&goals](const CellIndex& c) { return goals.count(CellKey(c)) > 0; };
  return NearestReachableFrontier(GridPathCosts::UpToNearestGoal(grid, start_m, is_goal, params),
                                  regions, skip);
}

}  // namespace slamkit
