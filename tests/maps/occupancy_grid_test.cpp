#include "slamkit/maps/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <ostream>
#include <random>
#include <utility>
#include <vector>

namespace slamkit {

// Found by argument-dependent lookup, so gtest prints cells readably.
static void PrintTo(const CellIndex& c, std::ostream* os) {
  *os << "(" << c.x << ", " << c.y << ")";
}

namespace {

using Cells = std::vector<CellIndex>;

Cells Reversed(Cells cells) {
  std::reverse(cells.begin(), cells.end());
  return cells;
}

TEST(RayCells, SingleCellHorizontalVerticalAndDiagonal) {
  EXPECT_EQ(RayCells({3, 4}, {3, 4}), (Cells{{3, 4}}));
  EXPECT_EQ(RayCells({0, 0}, {3, 0}), (Cells{{0, 0}, {1, 0}, {2, 0}, {3, 0}}));
  EXPECT_EQ(RayCells({3, 0}, {0, 0}), (Cells{{3, 0}, {2, 0}, {1, 0}, {0, 0}}));
  EXPECT_EQ(RayCells({2, 1}, {2, -2}), (Cells{{2, 1}, {2, 0}, {2, -1}, {2, -2}}));
  EXPECT_EQ(RayCells({0, 0}, {3, 3}), (Cells{{0, 0}, {1, 1}, {2, 2}, {3, 3}}));
  EXPECT_EQ(RayCells({0, 0}, {-2, 2}), (Cells{{0, 0}, {-1, 1}, {-2, 2}}));
  EXPECT_EQ(RayCells({1, 1}, {-1, -1}), (Cells{{1, 1}, {0, 0}, {-1, -1}}));
  EXPECT_EQ(RayCells({-1, 1}, {1, -1}), (Cells{{-1, 1}, {0, 0}, {1, -1}}));
}

// Slopes 2/5 and 5/2 in all eight octants; the true line never passes half-way between cells.
TEST(RayCells, ShallowAndSteepLinesInAllOctants) {
  EXPECT_EQ(RayCells({0, 0}, {5, 2}), (Cells{{0, 0}, {1, 0}, {2, 1}, {3, 1}, {4, 2}, {5, 2}}));
  EXPECT_EQ(RayCells({0, 0}, {2, 5}), (Cells{{0, 0}, {0, 1}, {1, 2}, {1, 3}, {2, 4}, {2, 5}}));
  EXPECT_EQ(RayCells({0, 0}, {-2, 5}),
            (Cells{{0, 0}, {0, 1}, {-1, 2}, {-1, 3}, {-2, 4}, {-2, 5}}));
  EXPECT_EQ(RayCells({0, 0}, {-5, 2}),
            (Cells{{0, 0}, {-1, 0}, {-2, 1}, {-3, 1}, {-4, 2}, {-5, 2}}));
  EXPECT_EQ(RayCells({0, 0}, {-5, -2}),
            (Cells{{0, 0}, {-1, 0}, {-2, -1}, {-3, -1}, {-4, -2}, {-5, -2}}));
  EXPECT_EQ(RayCells({0, 0}, {-2, -5}),
            (Cells{{0, 0}, {0, -1}, {-1, -2}, {-1, -3}, {-2, -4}, {-2, -5}}));
  EXPECT_EQ(RayCells({0, 0}, {2, -5}),
            (Cells{{0, 0}, {0, -1}, {1, -2}, {1, -3}, {2, -4}, {2, -5}}));
  EXPECT_EQ(RayCells({0, 0}, {5, -2}),
            (Cells{{0, 0}, {1, 0}, {2, -1}, {3, -1}, {4, -2}, {5, -2}}));
  // Away from the origin, and backwards.
  EXPECT_EQ(RayCells({15, -1}, {10, -3}),
            (Cells{{15, -1}, {14, -1}, {13, -2}, {12, -2}, {11, -3}, {10, -3}}));
}

// When the true line passes exactly half-way between two cells, the smaller minor coordinate wins,
// from whichever end the ray starts.
TEST(RayCells, TiesGoToTheSmallerMinorCoordinateInBothDirections) {
  EXPECT_EQ(RayCells({0, 0}, {2, 1}), (Cells{{0, 0}, {1, 0}, {2, 1}}));
  EXPECT_EQ(RayCells({2, 1}, {0, 0}), (Cells{{2, 1}, {1, 0}, {0, 0}}));
  EXPECT_EQ(RayCells({0, 0}, {2, -1}), (Cells{{0, 0}, {1, -1}, {2, -1}}));
  EXPECT_EQ(RayCells({2, -1}, {0, 0}), (Cells{{2, -1}, {1, -1}, {0, 0}}));
  EXPECT_EQ(RayCells({0, 0}, {1, 2}), (Cells{{0, 0}, {0, 1}, {1, 2}}));
  EXPECT_EQ(RayCells({1, 2}, {0, 0}), (Cells{{1, 2}, {0, 1}, {0, 0}}));
  EXPECT_EQ(RayCells({0, 0}, {-1, 2}), (Cells{{0, 0}, {-1, 1}, {-1, 2}}));
}

// Random rays: connected, one cell per major-axis step, each cell the true line's rounded minor
// coordinate, and the reversed ray is the same list reversed.
TEST(RayCells, RandomRaysAreDigitalLinesAndReverseExactly) {
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> coord(-40, 40);
  for (int trial = 0; trial < 2000; ++trial) {
    const CellIndex a{coord(rng), coord(rng)};
    const CellIndex b{coord(rng), coord(rng)};
    const Cells cells = RayCells(a, b);
    const int dx = b.x - a.x;
    const int dy = b.y - a.y;
    const int n = std::max(std::abs(dx), std::abs(dy));
    ASSERT_EQ(static_cast<int>(cells.size()), n + 1);
    EXPECT_EQ(cells.front(), a);
    EXPECT_EQ(cells.back(), b);
    for (int k = 0; k < n; ++k) {
      EXPECT_LE(std::abs(cells[k + 1].x - cells[k].x), 1);
      EXPECT_LE(std::abs(cells[k + 1].y - cells[k].y), 1);
      const double t = static_cast<double>(k) / n;
      EXPECT_LE(std::abs(cells[k].x - (a.x + t * dx)), 0.5 + 1e-9);
      EXPECT_LE(std::abs(cells[k].y - (a.y + t * dy)), 0.5 + 1e-9);
    }
    EXPECT_EQ(RayCells(b, a), Reversed(cells));
  }
}

TEST(OccupancyGrid, CellGeometryAndProbability) {
  OccupancyGrid grid({.resolution_m = 0.05});
  EXPECT_EQ(grid.WorldToCell({0.0, 0.0}), (CellIndex{0, 0}));
  EXPECT_EQ(grid.WorldToCell({0.049, 0.051}), (CellIndex{0, 1}));
  EXPECT_EQ(grid.WorldToCell({-0.001, -0.051}), (CellIndex{-1, -2}));
  EXPECT_TRUE(grid.CellCenter({-1, 2}).isApprox(Eigen::Vector2d(-0.025, 0.125)));
  EXPECT_EQ(grid.WorldToCell(grid.CellCenter({-7, 13})), (CellIndex{-7, 13}));
  EXPECT_DOUBLE_EQ(grid.Probability({5, 5}), 0.5);
  EXPECT_FALSE(grid.IsKnown({5, 5}));
  grid.Update({5, 5}, 2.0f);
  EXPECT_DOUBLE_EQ(grid.Probability({5, 5}), 1.0 - 1.0 / (1.0 + std::exp(2.0)));
}

TEST(OccupancyGrid, UpdatesAreClamped) {
  OccupancyGrid grid({.log_odds_min = -2.0f, .log_odds_max = 3.0f});
  grid.Update({1, 1}, 2.5f);
  grid.Update({1, 1}, 2.5f);
  EXPECT_FLOAT_EQ(grid.LogOdds({1, 1}), 3.0f);
  grid.Update({1, 1}, -0.5f);
  EXPECT_FLOAT_EQ(grid.LogOdds({1, 1}), 2.5f);
  grid.Update({1, 1}, -100.0f);
  EXPECT_FLOAT_EQ(grid.LogOdds({1, 1}), -2.0f);
}

TEST(OccupancyGrid, BoundsFollowTheWrittenCells) {
  OccupancyGrid grid;
  EXPECT_GT(grid.min_cell().x, grid.max_cell().x);
  EXPECT_EQ(grid.TileCount(), 0u);
  grid.Update({3, -2}, 0.1f);
  EXPECT_EQ(grid.min_cell(), (CellIndex{3, -2}));
  EXPECT_EQ(grid.max_cell(), (CellIndex{3, -2}));
  grid.Update({-5, 7}, 0.1f);
  grid.Update({1, 0}, 0.1f);
  EXPECT_EQ(grid.min_cell(), (CellIndex{-5, -2}));
  EXPECT_EQ(grid.max_cell(), (CellIndex{3, 7}));
}

// Writes far away in every direction re-table the tiles; every value written before survives.
TEST(OccupancyGrid, GrowthInAllDirectionsPreservesValues) {
  OccupancyGrid grid({.log_odds_min = -3.9f, .log_odds_max = 3.9f});
  const std::vector<CellIndex> cells = {{0, 0},      {1, 1},      {-1, -1},    {63, 64},
                                        {-64, -65},  {-500, -700}, {900, 1200}, {-3000, 5},
                                        {4000, -17}, {7, -9000},  {-2, 8000},  {-6000, -6000}};
  std::map<std::pair<int, int>, float> written;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const float value = 0.25f * static_cast<float>(i + 1);  // exact in the 1/32 steps
    grid.Update(cells[i], value);
    written[{cells[i].x, cells[i].y}] = value;
    for (const auto& [xy, v] : written) {
      ASSERT_EQ(grid.LogOdds({xy.first, xy.second}), v) << "after writing cell " << i;
    }
  }
  EXPECT_EQ(grid.LogOdds({2, 2}), 0.0f);
  EXPECT_EQ(grid.LogOdds({-500, -699}), 0.0f);
  EXPECT_EQ(grid.LogOdds({100000, -100000}), 0.0f);
  // Tiles: (0,0) (-1,-1) (0,1) (-1,-2) and one per far cell.
  EXPECT_EQ(grid.TileCount(), 11u);
}

TEST(OccupancyGrid, CopyOnWriteUnsharesOnlyTheWrittenTile) {
  OccupancyGrid original;
  original.Update({0, 0}, 1.0f);
  original.Update({100, 0}, 1.5f);
  original.Update({0, -100}, -1.0f);
  ASSERT_EQ(original.TileCount(), 3u);
  EXPECT_EQ(original.SharedTileCount(), 0u);

  OccupancyGrid copy = original;
  EXPECT_EQ(original.SharedTileCount(), 3u);
  EXPECT_EQ(copy.SharedTileCount(), 3u);

  copy.Update({101, 5}, 2.0f);
  EXPECT_EQ(copy.SharedTileCount(), 2u);
  EXPECT_EQ(original.SharedTileCount(), 2u);
  EXPECT_FLOAT_EQ(copy.LogOdds({101, 5}), 2.0f);
  EXPECT_FLOAT_EQ(copy.LogOdds({100, 0}), 1.5f);  // the unshared tile kept its old cells
  EXPECT_EQ(original.LogOdds({101, 5}), 0.0f);
  EXPECT_FLOAT_EQ(original.LogOdds({100, 0}), 1.5f);
  EXPECT_EQ(original.min_cell(), (CellIndex{0, -100}));
  EXPECT_EQ(original.max_cell(), (CellIndex{100, 0}));

  // Growing the copy's table moves tile pointers without unsharing them.
  copy.Update({-5000, 5000}, 1.0f);
  EXPECT_EQ(copy.TileCount(), 4u);
  EXPECT_EQ(copy.SharedTileCount(), 2u);
  EXPECT_EQ(original.TileCount(), 3u);
  EXPECT_EQ(original.LogOdds({-5000, 5000}), 0.0f);

  // Writing the original's side of a shared tile unshares it as well; the copy is unchanged.
  original.Update({0, 0}, 1.0f);
  EXPECT_EQ(original.SharedTileCount(), 1u);
  EXPECT_FLOAT_EQ(original.LogOdds({0, 0}), 2.0f);
  EXPECT_FLOAT_EQ(copy.LogOdds({0, 0}), 1.0f);
}

}  // namespace
}  // namespace slamkit

// Issue 8, items 4 and 5: coordinates and map sizes are checked before any int conversion or
// allocation.
TEST(OccupancyGridLimits, WorldToCellRejectsPointsOutsideTheExtent) {
  const slamkit::OccupancyGrid grid;
  EXPECT_THROW(grid.WorldToCell({1e308, 0.0}), std::out_of_range);
  EXPECT_THROW(grid.WorldToCell({0.0, -1e300}), std::out_of_range);
  EXPECT_THROW(grid.WorldToCell({std::nan(""), 0.0}), std::out_of_range);
  EXPECT_THROW(grid.WorldToCell({1.0e5 + 1.0, 0.0}), std::out_of_range);
  EXPECT_EQ(grid.WorldToCell({1.0e4, -1.0e4}), (slamkit::CellIndex{200000, -200000}));
  try {
    grid.WorldToCell({2.0e5, 0.0});
    FAIL();
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("max_extent_m"), std::string::npos) << e.what();
  }
}

TEST(OccupancyGridLimits, FineResolutionShrinksTheExtent) {
  const slamkit::OccupancyGrid grid({.resolution_m = 1e-9});
  EXPECT_LT(grid.extent_m(), 1.0);
  EXPECT_NO_THROW(grid.WorldToCell({0.5, 0.5}));
  EXPECT_THROW(grid.WorldToCell({30.0, 0.0}), std::out_of_range);
}

TEST(OccupancyGridLimits, BadResolutionIsRejected) {
  EXPECT_THROW(slamkit::OccupancyGrid({.resolution_m = 0.0}), std::invalid_argument);
  EXPECT_THROW(slamkit::OccupancyGrid({.resolution_m = -1.0}), std::invalid_argument);
  EXPECT_THROW(slamkit::OccupancyGrid({.resolution_m = std::nan("")}), std::invalid_argument);
}

TEST(OccupancyGridLimits, GrowingBeyondMaxCellsThrowsBeforeAllocating) {
  slamkit::OccupancyGrid grid;  // 0.05 m, max_cells 2^30
  grid.Update({0, 0}, 1.0f);
  // A jump of 1e4 m on both axes: 200000² cells, far beyond 2^30.
  const slamkit::CellIndex far = grid.WorldToCell({1.0e4, 1.0e4});
  try {
    grid.Update(far, 1.0f);
    FAIL();
  } catch (const std::length_error& e) {
    EXPECT_NE(std::string(e.what()).find("max_cells"), std::string::npos) << e.what();
  }
  EXPECT_EQ(grid.TileCount(), 1u);  // unchanged
  // The limit is a parameter: a small one stops a small map.
  slamkit::OccupancyGrid small({.max_cells = 64 * 64 * 4});
  small.Update({0, 0}, 1.0f);
  EXPECT_THROW(small.Update({64 * 10, 0}, 1.0f), std::length_error);
  // A map that fits grows with no error, even when the slack would not fit.
  EXPECT_NO_THROW(small.Update({64, 0}, 1.0f));
}
