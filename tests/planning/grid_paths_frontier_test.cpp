#include "slamkit/planning/grid_paths.hpp"

#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "grid_paths_fixtures.hpp"

// Paths simplified into legs, and the frontier target the explorer picks.
namespace slamkit::grid_paths_test {
namespace {

// Whether every point of the segment a-b lies over a free cell (sampled finely: a leg that clips
// the corner of a cell is caught, which a digital line would miss).
bool SegmentOverFreeCells(const GridPathCosts& costs, const Eigen::Vector2d& a,
                          const Eigen::Vector2d& b) {
  const int n = static_cast<int>(std::ceil((b - a).norm() / (0.01 * kRes))) + 1;
  for (int i = 0; i <= n; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (static_cast<double>(i) / n);
    if (!costs.IsFree({static_cast<int>(std::floor(p.x() / kRes)),
                       static_cast<int>(std::floor(p.y() / kRes))})) {
      return false;
    }
  }
  return true;
}

TEST(GridPathsSimplify, LegsAreShortKeepThePathsClearanceAndPassOverFreeCells) {
  OccupancyGrid grid = Room(50, 40);
  Fill(grid, 25, 1, 25, 27, '#');   // a wall to go round
  Fill(grid, 12, 18, 16, 24, ' ');  // an unknown patch: not inflated, yet never to be crossed
  const GridPathParams params;
  const double r = params.robot_radius_m, most = r + params.clearance_m;
  const GridPathCosts costs = GridPathCosts::From(grid, Centre({10, 10}), params);
  for (const CellIndex goal : {CellIndex{40, 10}, CellIndex{14, 30}, CellIndex{20, 21},
                               CellIndex{45, 35}, CellIndex{5, 35}}) {
    const std::vector<CellIndex> path = costs.PathTo(goal);
    ASSERT_FALSE(path.empty());
    for (const double max_segment : {2.0, 0.5}) {
      const std::vector<Eigen::Vector2d> w = SimplifyPath(costs, path, max_segment);
      ASSERT_GE(w.size(), 2u);
      EXPECT_LT((w.front() - Centre(path.front())).norm(), 1e-9);
      EXPECT_LT((w.back() - Centre(path.back())).norm(), 1e-9);
      std::size_t a = 0;  // the path index of w[i - 1]
      for (std::size_t i = 1; i < w.size(); ++i) {
        EXPECT_LE((w[i] - w[i - 1]).norm(), max_segment + 1e-9);
        EXPECT_TRUE(SegmentOverFreeCells(costs, w[i - 1], w[i]))
            << "goal " << goal.x << ", " << goal.y << " leg " << i;
        std::size_t b = a + 1;  // waypoints are path cells, in order
        while (b < path.size() && (Centre(path[b]) - w[i]).norm() > 1e-9) ++b;
        ASSERT_LT(b, path.size());
        double replaced = kInf;  // the least clearance of the cells the leg replaces
        for (std::size_t j = a + 1; j <= b; ++j)
          replaced = std::min(replaced, costs.Clearance(path[j]));
        for (const CellIndex& c : RayCells(path[a], path[b])) {
          if (c == path[a]) continue;
          EXPECT_GE(costs.Clearance(c), std::clamp(replaced, r, most));
        }
        a = b;
      }
    }
  }
  // In open space a path is one straight leg, cut into legs of at most max_segment_m.
  const GridPathCosts open = GridPathCosts::From(Room(40, 36), Centre({15, 15}), params);
  const std::vector<CellIndex> diagonal = open.PathTo({25, 22});
  EXPECT_EQ(SimplifyPath(open, diagonal, 2.0).size(), 2u);
  EXPECT_GE(SimplifyPath(open, diagonal, 0.5).size(), 4u);  // 1.22 m in legs of 0.5 m or less
  EXPECT_TRUE(SimplifyPath(open, {}).empty());
}

// A 3 × 3 m room entered at (22, 15), with openings to unexplored corridors at the top and the
// bottom, and a pocket beyond its closed right wall: nearer in a straight line, unreachable.
OccupancyGrid FrontierRooms() {
  OccupancyGrid grid = Room(30, 30);
  Fill(grid, 5, 29, 14, 35, '.');
  Fill(grid, 20, -6, 27, 0, '.');
  Fill(grid, 30, 10, 32, 20, '.');
  return grid;
}

TEST(GridPathsFrontier, PicksTheCheapestReachableCellAndHonoursSkip) {
  const OccupancyGrid grid = FrontierRooms();
  const std::vector<FrontierRegion> regions = FindFrontierRegions(grid);
  ASSERT_EQ(regions.size(), 3u);
  const Eigen::Vector2d start = Centre({22, 15});
  const GridPathCosts costs = GridPathCosts::From(grid, start);
  const auto cheapest = [&](const FrontierSkip& skip) {  // by brute force: region, cost
    std::pair<int, double> best = {-1, kInf};
    for (int i = 0; i < static_cast<int>(regions.size()); ++i) {
      if (skip && skip(regions[i])) continue;
      for (const CellIndex& c : regions[i].cells) {
        if (costs.Cost(c) < best.second) best = {i, costs.Cost(c)};
      }
    }
    return best;
  };
  const std::optional<FrontierTarget> target = NearestReachableFrontier(grid, regions, start);
  ASSERT_TRUE(target);
  EXPECT_EQ(target->region, cheapest({}).first);
  EXPECT_NEAR(target->cost_m, cheapest({}).second, 1e-12);
  EXPECT_EQ(target->cost_m, costs.Cost(target->cell));
  const std::vector<CellIndex>& cells = regions[target->region].cells;
  EXPECT_NE(std::find(cells.begin(), cells.end(), target->cell), cells.end());
  EXPECT_EQ(target->waypoints_m, SimplifyPath(costs, costs.PathTo(target->cell)));
  // The pocket's frontier is nearer in a straight line, but unreachable.
  ASSERT_TRUE(IsFrontierCell(grid, {32, 15}, GridFrontierParams{}));
  EXPECT_FALSE(costs.Reachable({32, 15}));
  EXPECT_LT((Centre({32, 15}) - start).norm(), (Centre(target->cell) - start).norm());
  // Skipping the chosen region gives the other reachable one; skipping all gives none.
  const Eigen::Vector2d chosen = regions[target->region].centroid_m;
  const FrontierSkip skip_chosen = [&](const FrontierRegion& r) {
    return (r.centroid_m - chosen).norm() < 1e-9;
  };
  const std::optional<FrontierTarget> second =
      NearestReachableFrontier(costs, regions, skip_chosen);
  ASSERT_TRUE(second);
  EXPECT_NE(second->region, target->region);
  EXPECT_EQ(second->region, cheapest(skip_chosen).first);
  EXPECT_GE(second->cost_m, target->cost_m);
  EXPECT_FALSE(
      NearestReachableFrontier(costs, regions, [](const FrontierRegion&) { return true; }));
}

// A hall of 300 × 200 cells (several 64-cell tiles) with pillars and wall stubs at seeded
// random places, and free rays out into the unknown beyond its east wall, as beams through a
// window leave them.

}  // namespace
}  // namespace slamkit::grid_paths_test
