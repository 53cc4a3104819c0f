#include "slamkit/eval/map_comparison.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <gtest/gtest.h>

namespace slamkit {
namespace {

constexpr std::uint8_t kFree = 254, kOccupied = 0, kUnknown = 205;

// A w × h map of free cells at 0.1 m, its lower-left corner at `origin`.
OccupancyImage FreeMap(int w, int h, Eigen::Vector2d origin = Eigen::Vector2d::Zero()) {
  OccupancyImage m;
  m.width = w;
  m.height = h;
  m.resolution_m = 0.1;
  m.origin_m = origin;
  m.pixels.assign(static_cast<std::size_t>(w * h), kFree);
  return m;
}

// Cell (x, y) from the lower-left corner.
void Set(OccupancyImage& m, int x, int y, std::uint8_t v) {
  m.pixels[static_cast<std::size_t>((m.height - 1 - y) * m.width + x)] = v;
}

TEST(CompareMaps, AMapAgainstItselfIsIdentical) {
  OccupancyImage a = FreeMap(20, 10);
  for (int x = 0; x < 20; ++x) Set(a, x, 0, kOccupied);
  for (int y = 5; y < 10; ++y) Set(a, 3, y, kUnknown);
  const MapComparison c = CompareMaps(a, a);
  EXPECT_EQ(c.cells, 200);
  EXPECT_EQ(c.known_cells, 195);
  EXPECT_EQ(c.kl_divergence, 0.0);
  EXPECT_EQ(c.cell_accuracy, 1.0);
  EXPECT_EQ(c.dice_occupied, 1.0);
}

// SPEC S4, Eq. 5 on hand-made grids: disjoint walls 0, a known overlap its value.
TEST(CompareMaps, DiceOfDisjointAndOverlappingWalls) {
  OccupancyImage a = FreeMap(10, 10), b = FreeMap(10, 10);
  for (int x = 1; x <= 4; ++x) Set(a, x, 2, kOccupied);
  for (int x = 5; x <= 8; ++x) Set(b, x, 2, kOccupied);
  EXPECT_EQ(CompareMaps(a, b).dice_occupied, 0.0);
  for (int x = 3; x <= 4; ++x) Set(b, x, 2, kOccupied);  // b: 3..8, a: 1..4, shared 3, 4
  EXPECT_DOUBLE_EQ(CompareMaps(a, b).dice_occupied, 2.0 * 2.0 / (4.0 + 6.0));
  EXPECT_DOUBLE_EQ(CompareMaps(a, b).cell_accuracy, 94.0 / 100.0);  // cells 1, 2 and 5..8 differ
}

// Eq. 24: each free cell made occupied adds the Bernoulli divergence of p = 1/255 (a free
// pixel) from q = 1 − floor (an occupied one, clamped), so the sum grows with the differences.
// A wall one cell apart in the two maps: Ψ 0 by Eq. 5, 1 with a tolerance of one cell; a wall
// two cells away still 0 with it; with k = 0 the tolerant count is Eq. 5 itself.
TEST(CompareMaps, ToleranceMatchesAWallOneCellAway) {
  OccupancyImage a = FreeMap(10, 10), b = FreeMap(10, 10), c = FreeMap(10, 10);
  for (int x = 1; x <= 8; ++x) Set(a, x, 4, kOccupied), Set(b, x, 5, kOccupied);
  for (int x = 1; x <= 8; ++x) Set(c, x, 6, kOccupied);
  MapComparisonParams tolerant;
  tolerant.dice_tolerance_cells = 1;
  EXPECT_EQ(CompareMaps(a, b).dice_occupied, 0.0);
  EXPECT_EQ(CompareMaps(a, b, tolerant).dice_occupied, 1.0);
  EXPECT_EQ(CompareMaps(a, c, tolerant).dice_occupied, 0.0);
  Set(c, 1, 5, kOccupied);  // one cell of c beside a's wall: a's (1,4), (2,4) and c's (1,5) match
  EXPECT_DOUBLE_EQ(CompareMaps(a, c, tolerant).dice_occupied, 3.0 / 17.0);
  tolerant.dice_tolerance_cells = -1;
  EXPECT_THROW(CompareMaps(a, b, tolerant), std::invalid_argument);
}

TEST(CompareMaps, KlDivergenceGrowsWithEachChangedCell) {
  const OccupancyImage a = FreeMap(10, 10);
  OccupancyImage b = a;
  const double p = 1.0 / 255.0, q = 1.0 - MapComparisonParams{}.probability_floor;
  const double per_cell = p * std::log(p / q) + (1.0 - p) * std::log((1.0 - p) / (1.0 - q));
  double previous = 0.0;
  for (int k = 1; k <= 5; ++k) {
    Set(b, k, k, kOccupied);
    const double kl = CompareMaps(a, b).kl_divergence;
    EXPECT_GT(kl, previous);
    EXPECT_NEAR(kl, k * per_cell, 1e-9 * k * per_cell);
    previous = kl;
  }
  EXPECT_GT(CompareMaps(b, a).kl_divergence, 0.0);  // not symmetric, but both positive
}

// Unknown in both maps is left out; unknown in one is the prior p = 0.5 against the other.
TEST(CompareMaps, UnknownCellsAreThePriorAndLeftOutWhenUnknownInBoth) {
  OccupancyImage a = FreeMap(4, 4), b = FreeMap(4, 4);
  a.pixels.assign(a.pixels.size(), kUnknown);
  b.pixels.assign(b.pixels.size(), kUnknown);
  const MapComparison none = CompareMaps(a, b);
  EXPECT_EQ(none.known_cells, 0);
  EXPECT_EQ(none.kl_divergence, 0.0);
  Set(b, 0, 0, kFree);
  const MapComparison one = CompareMaps(a, b);
  const double q = 1.0 / 255.0;
  EXPECT_EQ(one.known_cells, 1);
  EXPECT_EQ(one.cell_accuracy, 0.0);
  EXPECT_NEAR(one.kl_divergence, 0.5 * std::log(0.5 / q) + 0.5 * std::log(0.5 / (1.0 - q)), 1e-12);
}

// Maps with different origins are compared cell by cell where they overlap in the world.
TEST(CompareMaps, OverlapFollowsTheOrigins) {
  OccupancyImage world = FreeMap(30, 20);
  for (int x = 0; x < 30; ++x) Set(world, x, 12, kOccupied);
  // The same wall seen by a 10 × 10 map whose corner is at cell (5, 8) of the first.
  OccupancyImage part = FreeMap(10, 10, {0.5, 0.8});
  for (int x = 0; x < 10; ++x) Set(part, x, 4, kOccupied);
  const MapComparison c = CompareMaps(world, part);
  EXPECT_EQ(c.cells, 100);
  EXPECT_EQ(c.dice_occupied, 1.0);
  EXPECT_EQ(c.cell_accuracy, 1.0);
  part.origin_m.y() = 0.9;  // one cell up: the walls no longer meet
  EXPECT_EQ(CompareMaps(world, part).dice_occupied, 0.0);
}

TEST(CompareMaps, MismatchedGridsAndThresholdsAreRejected) {
  const OccupancyImage a = FreeMap(5, 5);
  OccupancyImage b = FreeMap(5, 5);
  b.resolution_m = 0.05;
  EXPECT_THROW(CompareMaps(a, b), std::invalid_argument);
  b = FreeMap(5, 5, {0.05, 0.0});  // half a cell
  EXPECT_THROW(CompareMaps(a, b), std::invalid_argument);
  MapComparisonParams p;
  p.free_threshold = 0.7;
  EXPECT_THROW(CompareMaps(a, a, p), std::invalid_argument);
  p = {};
  p.probability_floor = 0.0;
  EXPECT_THROW(CompareMaps(a, a, p), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
