#include "slamkit/sim/floor_plan_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace slamkit {
namespace {

constexpr long kFull = 127;  // OccupancyGrid's largest step count, either sign

// The cells a segment passes through, sampled every quarter cell: a cell it only grazes at a
// corner may be missed, which is why the flood fill is 4-connected (the wall stays closed to it).
template <class Visit>
void ForEachWallCell(const OccupancyGrid& grid, const WallSegment& wall, const Visit& visit) {
  const Eigen::Vector2d d = wall.second - wall.first;
  const int n = static_cast<int>(std::ceil(d.norm() / (0.25 * grid.resolution()))) + 1;
  for (int i = 0; i <= n; ++i) visit(grid.WorldToCell(wall.first + d * (double(i) / n)));
}

}  // namespace

OccupancyGrid FloorPlanOccupancy(const FloorPlan& plan, const OccupancyGridParams& params,
                                 const Eigen::Vector2d& inside_m) {
  OccupancyGrid grid(params);
  if (plan.walls.empty()) throw std::invalid_argument("FloorPlanOccupancy: no walls");
  CellIndex lo = grid.WorldToCell(plan.walls.front().first), hi = lo;
  for (const WallSegment& wall : plan.walls) {
    ForEachWallCell(grid, wall, [&](const CellIndex& c) {
      if (grid.LogOddsSteps(c) <= 0) grid.UpdateSteps(c, kFull);
      lo = {std::min(lo.x, c.x), std::min(lo.y, c.y)};
      hi = {std::max(hi.x, c.x), std::max(hi.y, c.y)};
    });
  }
  const CellIndex start = grid.WorldToCell(inside_m);
  if (start.x < lo.x || start.y < lo.y || start.x > hi.x || start.y > hi.y ||
      grid.LogOddsSteps(start) > 0) {
    throw std::invalid_argument("FloorPlanOccupancy: the inside point is on a wall or outside");
  }
  const int w = hi.x - lo.x + 1;
  std::vector<char> seen(static_cast<std::size_t>(w) * (hi.y - lo.y + 1), 0);
  auto index = [&](const CellIndex& c) { return std::size_t(c.y - lo.y) * w + (c.x - lo.x); };
  std::vector<CellIndex> stack = {start};
  seen[index(start)] = 1;
  while (!stack.empty()) {
    const CellIndex c = stack.back();
    stack.pop_back();
    grid.UpdateSteps(c, -kFull);
    for (const CellIndex n : {CellIndex{c.x + 1, c.y}, CellIndex{c.x - 1, c.y},
                              CellIndex{c.x, c.y + 1}, CellIndex{c.x, c.y - 1}}) {
      if (n.x < lo.x || n.y < lo.y || n.x > hi.x || n.y > hi.y || seen[index(n)]) continue;
      seen[index(n)] = 1;
      if (grid.LogOddsSteps(n) <= 0) stack.push_back(n);
    }
  }
  return grid;
}

}  // namespace slamkit
