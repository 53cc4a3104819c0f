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

namespace slamkit::grid_paths_test {
namespace {

TEST(GridPathCosts, ClearanceIsTheDistanceToTheNearestOccupiedSquare) {
  OccupancyGrid grid = Room(40, 30);
  Fill(grid, 12, 10, 15, 13, '#');  // a pillar, with cells inside it
  const GridPathParams params;      // reach 0.7 m
  const double reach = params.robot_radius_m + params.clearance_m;
  const GridPathCosts costs = GridPathCosts::From(grid, Centre({5, 20}), params);
  int checked_near = 0, checked_far = 0;
  ForEachCell(40, 30, [&](const CellIndex& c) {
    const double exact = ExactClearance(grid, c);
    if (exact < reach - 1e-9) {
      EXPECT_NEAR(costs.Clearance(c), exact, 1e-6) << c.x << ", " << c.y;
      ++checked_near;
    } else if (exact > reach + 1e-9) {
      EXPECT_EQ(costs.Clearance(c), kInf) << c.x << ", " << c.y;
      ++checked_far;
    }
    EXPECT_EQ(costs.IsFree(c), grid.Probability(c) < 0.35);
    EXPECT_EQ(costs.Traversable(c), costs.IsFree(c) && exact >= params.robot_radius_m - 1e-9);
  });
  EXPECT_GT(checked_near, 100);
  EXPECT_GT(checked_far, 10);
}

TEST(GridPathCosts, CostAwayFromWallsIsTheOctileDistance) {
  const OccupancyGrid grid = Room(40, 36);
  const CellIndex start{20, 18};
  const GridPathParams params;
  const GridPathCosts costs = GridPathCosts::From(grid, Centre(start), params);
  EXPECT_EQ(costs.start(), start);
  int core = 0, penalised = 0;
  ForEachCell(40, 36, [&](const CellIndex& c) {
    // The room is convex: every traversable cell is reachable, no other.
    EXPECT_EQ(costs.Reachable(c), costs.Traversable(c)) << c.x << ", " << c.y;
    if (!costs.Reachable(c)) return;
    if (std::isinf(costs.Clearance(c))) {  // the core, free of penalty, is a rectangle
      EXPECT_NEAR(costs.Cost(c), Octile(start, c), 1e-9) << c.x << ", " << c.y;
      ++core;
    } else {  // the last step into a cell near a wall pays a penalty
      EXPECT_GT(costs.Cost(c), Octile(start, c) + 1e-6) << c.x << ", " << c.y;
      ++penalised;
    }
  });
  EXPECT_GT(core, 300);
  EXPECT_GT(penalised, 100);
}

// Two rooms split by a wall at y = 20 with a gap of `gap` cells centred on x = 20.
OccupancyGrid SplitRoom(int gap) {
  OccupancyGrid grid = Room(41, 41);
  Fill(grid, 1, 20, 39, 20, '#');
  if (gap > 0) Fill(grid, 20 - gap / 2, 20, 20 - gap / 2 + gap - 1, 20, '.');
  return grid;
}

TEST(GridPathCosts, AGapNarrowerThanTheRobotBlocksAndOneCellWiderPasses) {
  const CellIndex start{20, 8}, goal{20, 32};
  for (int k = 2; k <= 8; ++k) {  // robot_radius_m = k / 2 cells
    GridPathParams params;
    params.robot_radius_m = 0.05 * k;
    params.clearance_m = 0.2;
    for (int gap = 0; gap <= 12; ++gap) {
      const GridPathCosts costs = GridPathCosts::From(SplitRoom(gap), Centre(start), params);
      ASSERT_TRUE(costs.Traversable(start));
      ASSERT_TRUE(costs.Traversable(goal));
      if (gap < k) {  // gap × 0.1 < 2 × radius
        EXPECT_FALSE(costs.Reachable(goal)) << "radius " << params.robot_radius_m << " gap " << gap;
        EXPECT_TRUE(costs.PathTo(goal).empty());
      } else if (gap >= k + 1) {  // at least 2 × radius + one cell
        EXPECT_TRUE(costs.Reachable(goal)) << "radius " << params.robot_radius_m << " gap " << gap;
        for (const CellIndex& c : costs.PathTo(goal)) EXPECT_TRUE(costs.Traversable(c));
      }
    }
  }
}

TEST(GridPathCosts, PathToIsAnOptimalChainOfNeighboursKeepingClear) {
  // A wall from the bottom up to y = 27 between start and goal: the path goes round its end.
  OccupancyGrid grid = Room(50, 40);
  Fill(grid, 25, 1, 25, 27, '#');
  const CellIndex start{10, 10}, goal{40, 10};
  const GridPathCosts costs = GridPathCosts::From(grid, Centre(start), GridPathParams{});
  const std::vector<CellIndex> path = costs.PathTo(goal);
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path.front(), start);
  EXPECT_EQ(path.back(), goal);
  double along = 0.0;
  for (std::size_t i = 1; i < path.size(); ++i) {
    ASSERT_EQ(std::max(std::abs(path[i].x - path[i - 1].x), std::abs(path[i].y - path[i - 1].y)),
              1);
    EXPECT_TRUE(costs.Traversable(path[i]));
    along += StepCost(costs, path[i - 1], path[i]);
    EXPECT_NEAR(costs.Cost(path[i]), along, 1e-9);
  }
  EXPECT_GT(path[path.size() / 2].y, 27);  // over the wall's end
  // Optimality: no step between traversable cells leads to a cheaper cost (Bellman).
  ForEachCell(50, 40, [&](const CellIndex& c) {
    if (!costs.Reachable(c) || !costs.Traversable(c)) return;
    ForEachCell(3, 3, [&](const CellIndex& d) {
      const CellIndex n{c.x + d.x - 1, c.y + d.y - 1};
      if (n == c || !costs.Traversable(n)) return;
      EXPECT_LE(costs.Cost(n), costs.Cost(c) + StepCost(costs, c, n) + 1e-9);
    });
  });
}

TEST(GridPathCosts, UnreachableCellsCostInfinityAndHaveNoPath) {
  OccupancyGrid grid = Room(40, 30);
  Fill(grid, 25, 5, 35, 20, '#');  // a closed box ...
  Fill(grid, 26, 6, 34, 19, '.');  // ... with free space inside
  Fill(grid, 5, 20, 8, 23, ' ');   // an unknown patch in the open room
  const GridPathCosts costs = GridPathCosts::From(grid, Centre({10, 10}), GridPathParams{});
  ASSERT_TRUE(costs.Traversable({30, 12}));
  for (const CellIndex c : {CellIndex{30, 12}, CellIndex{6, 21}, CellIndex{0, 0}, CellIndex{25, 10},
                            CellIndex{500, -300}}) {
    EXPECT_FALSE(costs.Reachable(c)) << c.x << ", " << c.y;
    EXPECT_EQ(costs.Cost(c), kInf);
    EXPECT_TRUE(costs.PathTo(c).empty());
  }
  EXPECT_TRUE(costs.Reachable({15, 15}));
}

TEST(GridPathCosts, AStartInTheInflationOnlyMovesAwayFromTheWall) {
  const OccupancyGrid grid = Room(40, 40);
  const CellIndex start{1, 20};  // against the left wall
  const GridPathCosts costs = GridPathCosts::From(grid, Centre(start), GridPathParams{});
  EXPECT_EQ(costs.Cost(start), 0.0);
  EXPECT_EQ(costs.PathTo(start), std::vector<CellIndex>{start});
  const std::vector<CellIndex> path = costs.PathTo({20, 20});
  ASSERT_FALSE(path.empty());
  for (std::size_t i = 1; i < path.size() && costs.Clearance(path[i]) < 0.3; ++i) {
    EXPECT_GT(costs.Clearance(path[i]), costs.Clearance(path[i - 1]));
  }
  // Along the wall, inside the inflation, nothing is reachable.
  for (const int y : {2, 10, 17, 23, 30, 38}) EXPECT_FALSE(costs.Reachable({1, y})) << y;
  // Before the first scan the start alone is reachable, whatever it holds.
  const GridPathCosts empty =
      GridPathCosts::From(OccupancyGrid(OccupancyGridParams{kRes}), {1.23, -4.56});
  EXPECT_EQ(empty.Cost(empty.start()), 0.0);
  EXPECT_FALSE(empty.Reachable({empty.start().x + 1, empty.start().y}));
}

OccupancyGrid PillaredHall() {
  OccupancyGrid grid = Room(300, 200);
  Rng rng(7);
  for (int k = 0; k < 60; ++k) {
    const int x = static_cast<int>(rng.Uniform(5, 290)), y = static_cast<int>(rng.Uniform(5, 190));
    const bool stub = k % 3 == 0;
    Fill(grid, x, y, x + (stub ? 12 : 2), y + (stub ? 0 : 2), '#');
  }
  Fill(grid, 299, 60, 299, 62, '.');  // the window
  for (int x = 300; x < 420; ++x) Fill(grid, x, 61 + (x - 300) / 6, x, 61 + (x - 300) / 6, '.');
  return grid;
}

// The distance to the nearest occupied square within `reach` cells, by brute force.
double ClearanceWithin(const OccupancyGrid& grid, const CellIndex& c, int reach) {
  double best = kInf;
  for (int y = c.y - reach; y <= c.y + reach; ++y) {
    for (int x = c.x - reach; x <= c.x + reach; ++x) {
      if (!(grid.Probability({x, y}) > 0.65)) continue;
      const double ex = std::max(std::abs(x - c.x) - 0.5, 0.0);
      const double ey = std::max(std::abs(y - c.y) - 0.5, 0.0);
      best = std::min(best, kRes * std::hypot(ex, ey));
    }
  }
  return best;
}

// The costs keep their tiles unprepared until the search reaches them: a search stopped early
// prepares few, and every figure must still be the one a full search gives, on every tile.
TEST(GridPathCosts, ASearchStoppedAtTheNearestGoalAgreesWithAFullOne) {
  const OccupancyGrid grid = PillaredHall();
  const GridPathParams params;
  const double reach = params.robot_radius_m + params.clearance_m;
  const Eigen::Vector2d start = Centre({40, 40});
  const CellIndex goal_a{150, 120}, goal_b{260, 30};
  const auto is_goal = [&](const CellIndex& c) { return c == goal_a || c == goal_b; };
  const GridPathCosts full = GridPathCosts::From(grid, start, params);
  const GridPathCosts early = GridPathCosts::UpToNearestGoal(grid, start, is_goal, params);
  ASSERT_TRUE(full.Reachable(goal_a) && full.Reachable(goal_b));
  ASSERT_TRUE(early.goal().has_value());
  const double goal_cost = std::min(full.Cost(goal_a), full.Cost(goal_b));
  EXPECT_EQ(early.Cost(*early.goal()), goal_cost);
  EXPECT_FALSE(full.goal().has_value());
  int settled = 0, beyond = 0, checked = 0;
  for (int y = -1; y <= 200; ++y) {  // the window: the written cells and a ring of one
    for (int x = -1; x <= 420; ++x) {
      const CellIndex c{x, y};
      ASSERT_EQ(early.IsFree(c), full.IsFree(c)) << x << ", " << y;
      ASSERT_EQ(early.Clearance(c), full.Clearance(c)) << x << ", " << y;
      const double exact = ClearanceWithin(grid, c, 10);
      if (exact < reach - 1e-9) {
        ASSERT_NEAR(full.Clearance(c), exact, 1e-9) << x << ", " << y;
        ++checked;
      }
      if (full.Cost(c) <= goal_cost) {
        ASSERT_EQ(early.Cost(c), full.Cost(c)) << x << ", " << y;
        ++settled;
      } else {
        ASSERT_GE(early.Cost(c), full.Cost(c)) << x << ", " << y;
        beyond += std::isfinite(full.Cost(c));
      }
    }
  }
  EXPECT_GT(settled, 5000);
  EXPECT_GT(beyond, 5000);
  EXPECT_GT(checked, 5000);
  // The ray beyond the window is reachable only cell by cell: unknown on both sides.
  EXPECT_TRUE(full.IsFree({350, 69}));
  EXPECT_EQ(full.PathTo({150, 120}).back(), (CellIndex{150, 120}));
  // No goal: the search runs to the end.
  const GridPathCosts none =
      GridPathCosts::UpToNearestGoal(grid, start, [](const CellIndex&) { return false; }, params);
  EXPECT_FALSE(none.goal().has_value());
  EXPECT_EQ(none.Cost({250, 180}), full.Cost({250, 180}));
}

TEST(GridPathCosts, InvalidParamsThrow) {
  const OccupancyGrid grid = Room(10, 10);
  const GridPathParams bad[] = {{.robot_radius_m = -0.1},        {.clearance_m = -0.1},
                                {.clearance_cost_weight = -1.0}, {.free_probability = 0.0},
                                {.free_probability = 0.7},       {.occupied_probability = 1.0},
                                {.robot_radius_m = std::nan("")}};
  for (const GridPathParams& p : bad) {
    EXPECT_THROW(GridPathCosts::From(grid, {0.5, 0.5}, p), std::invalid_argument);
    EXPECT_THROW(NearestReachableFrontier(grid, {}, {0.5, 0.5}, p), std::invalid_argument);
  }
  const GridPathParams edge = {.robot_radius_m = 0.0,
                               .clearance_m = 0.0,
                               .clearance_cost_weight = 0.0,
                               .free_probability = 0.5,
                               .occupied_probability = 0.5};
  EXPECT_NO_THROW(GridPathCosts::From(grid, {0.5, 0.5}, edge));
}

}  // namespace
}  // namespace slamkit::grid_paths_test
