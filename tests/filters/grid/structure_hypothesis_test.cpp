#include "slamkit/filters/grid/structure_hypothesis.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace slamkit {
namespace {

OccupancyGridParams TenCentimetres() {
  OccupancyGridParams params;
  params.resolution_m = 0.1;
  return params;
}

// An L of occupied cells (10 along x from the origin, 5 along y) with free cells beside it.
OccupancyGrid LShape() {
  OccupancyGrid h(TenCentimetres());
  for (int x = 0; x < 10; ++x) h.UpdateSteps({x, 0}, 100), h.UpdateSteps({x, 1}, -50);
  for (int y = 1; y < 5; ++y) h.UpdateSteps({0, y}, 100);
  return h;
}

TEST(StructureHypothesis, MovedByIdentityIsACopy) {
  const OccupancyGrid h = LShape();
  OccupancyGrid layer(TenCentimetres());
  AddMovedHypothesis(h, Pose2(), layer);
  for (int y = -2; y < 8; ++y) {
    for (int x = -2; x < 12; ++x) EXPECT_EQ(layer.LogOddsSteps({x, y}), h.LogOddsSteps({x, y}));
  }
}

// A quarter turn about the origin and a shift of (2, 1) m: cell (x, y) lands on (19 − y, 10 + x)
// (cell centres turn onto cell centres), with no hole.
TEST(StructureHypothesis, MovesCellsByTheTransformWithoutHoles) {
  const OccupancyGrid h = LShape();
  OccupancyGrid layer(TenCentimetres());
  AddMovedHypothesis(h, Pose2(2.0, 1.0, std::numbers::pi / 2), layer);
  int known = 0;
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 30; ++x) known += layer.IsKnown({x, y});
  }
  int expected = 0;
  for (int y = -2; y < 8; ++y) {
    for (int x = -2; x < 12; ++x) expected += h.IsKnown({x, y});
  }
  EXPECT_EQ(known, expected);
  for (int x = 0; x < 10; ++x) {
    EXPECT_EQ(layer.LogOddsSteps({19, 10 + x}), 100) << x;  // the long arm, now along y
    EXPECT_EQ(layer.LogOddsSteps({18, 10 + x}), h.LogOddsSteps({x, 1})) << x;  // its inner side
  }
}

TEST(StructureHypothesis, KeepsWhatTheLayerAlreadyHolds) {
  const OccupancyGrid h = LShape();
  OccupancyGrid layer(TenCentimetres());
  layer.UpdateSteps({3, 0}, -20);
  AddMovedHypothesis(h, Pose2(), layer);
  EXPECT_EQ(layer.LogOddsSteps({3, 0}), -20);
  EXPECT_EQ(layer.LogOddsSteps({4, 0}), 100);
}

// A wall predicted at x = 5 m, a map explored up to x = 2 m: beams ending on the wall are hits,
// beams ending short of it on predicted free cells are not, beams ending in explored cells or
// where nothing is predicted do not count.
TEST(StructureHypothesis, MeasuresTheHitRatioOnUnexploredCellsOnly) {
  OccupancyGrid h(TenCentimetres());
  for (int y = -20; y < 20; ++y) {
    h.UpdateSteps({50, y}, 100);
    for (int x = 20; x < 50; ++x) h.UpdateSteps({x, y}, -50);
  }
  OccupancyGrid map(TenCentimetres());
  for (int y = -20; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) map.UpdateSteps({x, y}, -50);
  }
  ScanPoints points;
  for (double y : {-1.0, -0.5, 0.0, 0.5, 1.0}) points.ends.emplace_back(5.05, y);  // on the wall
  for (double y : {-0.5, 0.5}) points.ends.emplace_back(3.55, y);  // short of it
  points.ends.emplace_back(1.05, 0.0);                              // explored
  points.ends.emplace_back(8.05, 0.0);                              // beyond the prediction
  const HypothesisSupport support = MeasureSupport(h, Pose2(), map, points, Pose2());
  EXPECT_EQ(support.beams, 7);
  EXPECT_EQ(support.hits, 5);
  EXPECT_NEAR(support.HitRatio(), 5.0 / 7.0, 1e-12);
  // The particle 0.3 m further along x, the hypothesis moved with it: the same beams.
  const Pose2 shift(0.3, 0.0, 0.0);
  OccupancyGrid shifted_map(TenCentimetres());
  AddMovedHypothesis(map, shift, shifted_map);
  const HypothesisSupport moved = MeasureSupport(h, shift, shifted_map, points, shift);
  EXPECT_EQ(moved.beams, 7);
  EXPECT_EQ(moved.hits, 5);
}

TEST(StructureHypothesis, CountsTheCellsTheMapHasNotExploredYet) {
  const OccupancyGrid h = LShape();  // 10 + 10 + 3 cells ((0, 1) is in both arms)
  OccupancyGrid map(TenCentimetres());
  EXPECT_EQ(UnexploredCells(h, Pose2(), map), 23);
  for (int x = 0; x < 5; ++x) map.UpdateSteps({x, 0}, 10);
  EXPECT_EQ(UnexploredCells(h, Pose2(), map), 18);
  // Seen through a shift of one cell along x, the map's cells cover h's cells 1..5 instead.
  EXPECT_EQ(UnexploredCells(h, Pose2(-0.1, 0.0, 0.0), map), 18);
  EXPECT_EQ(UnexploredCells(h, Pose2(0.0, 5.0, 0.0), map), 23);
}

}  // namespace
}  // namespace slamkit
