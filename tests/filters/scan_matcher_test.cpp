#include <gtest/gtest.h>

#include "common/synthetic_room.hpp"
#include "slamkit/filters/resampling.hpp"
#include "slamkit/filters/scan_matcher.hpp"

namespace slamkit {
namespace {

using testing::RoomScan;

OccupancyGrid RoomMap() {
  OccupancyGrid grid;
  for (const Pose2& p : {Pose2(0, 0, 0), Pose2(0, 0, M_PI), Pose2(-4, -2, M_PI / 2),
                         Pose2(5, 2, -M_PI / 2), Pose2(0, 3, 0), Pose2(0, -3, M_PI)}) {
    InsertScan(grid, p, RoomScan(p));
  }
  return grid;
}

TEST(ScanMatcher, RecoversKnownOffsetOnSyntheticMap) {
  const OccupancyGrid grid = RoomMap();
  const ScanMatcherParams params;
  for (const Pose2& truth : {Pose2(0.5, 0.3, 0.2), Pose2(-2.0, -1.0, -1.0), Pose2(2, 2.5, 2.5)}) {
    const ScanPoints points = PrepareScan(RoomScan(truth), params);
    const Pose2 guess = truth.Compose(Pose2(0.15, -0.1, 0.05));
    const MatchResult m = MatchScan(grid, points, guess, params);
    EXPECT_TRUE(m.accepted);
    // Within one cell: the map itself puts a wall at a cell centre, up to half a cell off.
    EXPECT_LT((m.pose.translation() - truth.translation()).norm(), 0.05);
    EXPECT_LT(std::abs(WrapAngle(m.pose.theta() - truth.theta())), 0.01);
    // The truth scores better than the guess it started from.
    EXPECT_GT(EvaluatePose(grid, points, truth, params).score,
              EvaluatePose(grid, points, guess, params).score);
  }
}

TEST(Resampling, SystematicKeepsHeavyParticlesAndNeffMeasuresSpread) {
  Rng rng(3);
  const std::vector<double> one_heavy = {0.0, 1.0, 0.0, 0.0};
  EXPECT_EQ(SystematicResample(one_heavy, rng), (std::vector<int>{1, 1, 1, 1}));
  EXPECT_NEAR(EffectiveSampleSize(one_heavy), 1.0, 1e-12);
  const std::vector<double> uniform = {0.25, 0.25, 0.25, 0.25};
  EXPECT_EQ(SystematicResample(uniform, rng), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_NEAR(EffectiveSampleSize(uniform), 4.0, 1e-12);
  const std::vector<double> w = NormaliseLogWeights(std::vector<double>{-1000.0, -1000.0 + std::log(3.0)});
  EXPECT_NEAR(w[0], 0.25, 1e-12);
  EXPECT_NEAR(w[1], 0.75, 1e-12);
}

}  // namespace
}  // namespace slamkit
