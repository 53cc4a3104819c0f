#include "slamkit/planning/grid_frontiers.hpp"

#include <stdexcept>

#include <gtest/gtest.h>

namespace slamkit {
namespace {

// A 20 × 10 room of free cells at 0.1 m, walled (occupied) on the left, top and bottom; its
// right side (x = 19) borders the unknown.
OccupancyGrid OpenRoom() {
  OccupancyGrid grid(OccupancyGridParams{0.1});
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 20; ++x) {
      const bool wall = x == 0 || y == 0 || y == 9;
      grid.Update({x, y}, wall ? 3.0f : -3.0f);
    }
  }
  return grid;
}

TEST(GridFrontiers, TheOpenSideOfARoomIsOneRegion) {
  const std::vector<FrontierRegion> regions = FindFrontierRegions(OpenRoom());
  ASSERT_EQ(regions.size(), 1u);
  // The free cells of column 19 (rows 1..8) border the unknown; walls never are frontiers.
  ASSERT_EQ(regions[0].cells.size(), 8u);
  for (const CellIndex& c : regions[0].cells) EXPECT_EQ(c.x, 19);
  EXPECT_NEAR(regions[0].centroid_m.x(), 1.95, 1e-12);
  EXPECT_NEAR(regions[0].centroid_m.y(), 0.5, 1e-12);
}

TEST(GridFrontiers, AHoleOfOneCellIsNoiseAndTwoOpeningsAreTwoRegions) {
  OccupancyGrid grid = OpenRoom();
  // Cell (10, 5) unknown again: its four free neighbours touch it, fewer than 5 cells.
  grid.Update({10, 5}, -grid.LogOdds({10, 5}));
  ASSERT_FALSE(grid.IsKnown({10, 5}));
  EXPECT_EQ(FindFrontierRegions(grid).size(), 1u);
  GridFrontierParams keep_all;
  keep_all.min_region_cells = 1;
  EXPECT_EQ(FindFrontierRegions(grid, keep_all).size(), 2u);
  // Closing the middle of the open side splits it in two, the larger first.
  OccupancyGrid split_room = OpenRoom();
  for (int y = 3; y <= 4; ++y) split_room.Update({19, y}, 6.0f);
  const std::vector<FrontierRegion> split = FindFrontierRegions(split_room, keep_all);
  ASSERT_EQ(split.size(), 2u);
  EXPECT_EQ(split[0].cells.size(), 4u);  // rows 5..8
  EXPECT_EQ(split[1].cells.size(), 2u);  // rows 1..2
  EXPECT_EQ(FindFrontierRegions(split_room).size(), 0u);  // both below 5 cells
}

// InFrontierRegion grows a region only until it is large enough: it must agree with the regions
// FindFrontierRegions keeps, cell by cell, across tiles, for small and large regions.
TEST(GridFrontiers, InFrontierRegionAgreesWithTheRegionsKept) {
  OccupancyGrid grid(OccupancyGridParams{0.1});
  for (int y = 0; y < 150; ++y) {
    for (int x = 0; x < 200; ++x) grid.Update({x, y}, (x % 37 == 0 || y == 0) ? 3.0f : -3.0f);
  }
  for (int k = 0; k < 6; ++k) {  // holes of 1 to 6 cells in a row: regions of 4 to 14 cells
    for (int i = 0; i <= k; ++i) grid.Update({10 + 30 * k + i, 70}, -grid.LogOdds({10 + 30 * k + i, 70}));
  }
  for (int x = 200; x < 260; ++x) grid.Update({x, 100 + (x - 200) / 4}, -3.0f);  // a ray out
  for (int min_cells : {1, 5, 8, 12}) {
    GridFrontierParams p;
    p.min_region_cells = min_cells;
    std::vector<char> kept(300 * 200, 0);
    for (const FrontierRegion& r : FindFrontierRegions(grid, p)) {
      for (const CellIndex& c : r.cells) kept[std::size_t(c.y + 10) * 300 + (c.x + 10)] = 1;
    }
    int in = 0;
    for (int y = -10; y < 190; ++y) {
      for (int x = -10; x < 290; ++x) {
        const bool inside = InFrontierRegion(grid, {x, y}, p);
        ASSERT_EQ(inside, kept[std::size_t(y + 10) * 300 + (x + 10)] != 0)
            << x << ", " << y << ", min " << min_cells;
        in += inside;
      }
    }
    EXPECT_GT(in, 100) << min_cells;
  }
}

TEST(GridFrontiers, AnEmptyGridHasNoneAndBadParamsAreRejected) {
  EXPECT_TRUE(FindFrontierRegions(OccupancyGrid()).empty());
  GridFrontierParams p;
  p.free_probability = 1.0;
  EXPECT_THROW(FindFrontierRegions(OpenRoom(), p), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
