#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "common/synthetic_room.hpp"
#include "slamkit/filters/grid/rbpf_grid_slam.hpp"
#include "slamkit/filters/grid/scan_matcher.hpp"
#include "slamkit/sim/laser_sim.hpp"
#include "common/ordered_draws.hpp"

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
    const ScanPoints points = PrepareScan(RoomScan(truth), 30.0, params);
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

// The score written out cell by cell, as EvaluatePose documents it: the reference for its
// one-lookup-per-tile fast path, which must agree exactly, near tile edges too.
MatchQuality ReferenceEvaluate(const OccupancyGrid& grid, const ScanPoints& points,
                               const Pose2& pose, const ScanMatcherParams& params) {
  MatchQuality q;
  const double r = grid.resolution();
  const double miss_sq = std::pow((params.search_cells + 1) * r, 2);
  for (std::size_t i = 0; i < points.ends.size(); ++i) {
    // score_sigma_per_m: σ grows with the beam's range, the window with σ.
    const double sigma = std::sqrt(std::pow(params.score_sigma_m, 2) +
                                   std::pow(params.score_sigma_per_m * points.ends[i].norm(), 2));
    const int window = std::max(params.search_cells, int(std::ceil(sigma / r)));
    const Eigen::Vector2d end = pose.rotation() * points.ends[i] + pose.translation();
    const Eigen::Vector2d dir = pose.rotation() * points.directions[i];
    const CellIndex c = grid.WorldToCell(end), f = grid.WorldToCell(end - r * dir);
    double best = std::numeric_limits<double>::infinity();
    for (int dx = -window; dx <= window; ++dx) {
      for (int dy = -window; dy <= window; ++dy) {
        if (grid.LogOdds({c.x + dx, c.y + dy}) > 0 && grid.LogOdds({f.x + dx, f.y + dy}) < 0) {
          best = std::min(best, (grid.CellCenter({c.x + dx, c.y + dy}) - end).squaredNorm());
        }
      }
    }
    const double d_sq = std::min(best, miss_sq);
    if (std::isfinite(best)) {
      ++q.matched;
      q.score += std::exp(-best / (sigma * sigma));
    }
    q.log_likelihood -= d_sq * 0.5 / std::pow(params.likelihood_sigma_m, 2);
  }
  return q;
}

TEST(ScanMatcher, EvaluatePoseEqualsTheCellByCellDefinition) {
  const OccupancyGrid grid = RoomMap();
  const OccupancyGrid empty;
  Rng rng(11);
  // Windows of 1 and 3 cells, and range-scaled ones (up to 5 cells in this room).
  const std::pair<int, double> cases[] = {{1, 0.0}, {3, 0.0}, {1, 0.02}};
  for (const auto& [window, per_m] : cases) {
    ScanMatcherParams params;
    params.search_cells = window;
    params.score_sigma_per_m = per_m;
    for (int k = 0; k < 200; ++k) {
      const Pose2 truth(testing::UniformVector3(rng, {-6, -4, -M_PI}, {6, 4, M_PI}));
      const ScanPoints points = PrepareScan(RoomScan(truth), 30.0, params);
      const Pose2 pose =
          truth.Compose(Pose2(testing::NormalVector3(rng, 0.05, 0.05, 0.02)));
      const MatchQuality got = EvaluatePose(grid, points, pose, params);
      const MatchQuality want = ReferenceEvaluate(grid, points, pose, params);
      ASSERT_EQ(got.matched, want.matched) << "window " << window << ", pose " << k;
      ASSERT_NEAR(got.score, want.score, 1e-9 * points.ends.size());
      ASSERT_NEAR(got.log_likelihood, want.log_likelihood, 1e-9 * points.ends.size());
      // The likelihood-only evaluation sums the same terms in the same order.
      ASSERT_EQ(ScanLogLikelihood(grid, points, pose, params), got.log_likelihood);
      // The layered view searches cell by cell, never within one tile, and must round as the
      // tile path does: a score may not depend on how the map is stored.
      const MatchQuality layered = EvaluatePose(GridMapView(empty, &grid), points, pose, params);
      ASSERT_EQ(layered.matched, want.matched);
      ASSERT_EQ(layered.score, got.score) << "window " << window << ", pose " << k;
      ASSERT_EQ(layered.log_likelihood, got.log_likelihood);
    }
  }
}

// EvaluatePoseAbove gives up only on a pose whose whole score stays below the bound, and
// otherwise returns EvaluatePose's quality exactly: a climb pruning with it decides alike.
TEST(ScanMatcher, EvaluatePoseAboveGivesUpOnlyBelowItsBound) {
  const OccupancyGrid grid = RoomMap();
  Rng rng(12);
  const ScanMatcherParams params;
  int pruned = 0;
  for (int k = 0; k < 100; ++k) {
    const Pose2 truth(testing::UniformVector3(rng, {-6, -4, -M_PI}, {6, 4, M_PI}));
    const ScanPoints points = PrepareScan(RoomScan(truth), 30.0, params);
    const Pose2 pose = truth.Compose(Pose2(testing::NormalVector3(rng, 0.05, 0.05, 0.02)));
    const MatchQuality full = EvaluatePose(grid, points, pose, params);
    for (double offset : {-30.0, -1.0, -1e-3, 1e-3, 1.0, 30.0}) {
      const std::optional<MatchQuality> q =
          EvaluatePoseAbove(grid, points, pose, params, full.score + offset);
      if (!q) {
        ASSERT_LT(full.score, full.score + offset) << k;
        ++pruned;
        continue;
      }
      ASSERT_EQ(q->score, full.score) << k;
      ASSERT_EQ(q->log_likelihood, full.log_likelihood) << k;
      ASSERT_EQ(q->matched, full.matched) << k;
    }
  }
  // A bound 30 above the score leaves the last 30 beams unable to reach it: such poses stop early.
  EXPECT_GE(pruned, 100);
}

// A corridor whose far part is not mapped yet: nothing but the mapped part's end tells where the
// scan lies along the corridor, and a plain climb drifts along it toward the mapped part, where
// more beams find a wall (by 4 cm here).
struct HalfMappedCorridor {
  FloorPlan plan{{{{-2.0, -1.025}, {20.0, -1.025}}, {{-2.0, 1.025}, {20.0, 1.025}}}};
  OccupancyGrid grid;
  Pose2 truth{0.6, 0.0, 0.0};
  Pose2 guess{0.6, 0.04, 0.0};  // right along the corridor, 4 cm off across it

  HalfMappedCorridor() {
    ScanInsertionParams insertion;
    insertion.usable_range_m = 4.0;  // maps x up to about 4 m only
    InsertScan(grid, Pose2(), ScanAt(Pose2()), insertion);
  }
  LaserScan ScanAt(const Pose2& pose) const {
    Rng rng(1);
    LaserSimParams laser;
    laser.sigma_range_m = 0.0;
    return SimulateScan(plan, pose, laser, rng);
  }
  MatchResult Match(const ScanMatcherParams& params) const {
    return MatchScan(grid, PrepareScan(ScanAt(truth), 8.0, params), guess, params);
  }
};

// The prior holds the guess along the corridor and still reduces the sideways offset, which the
// walls constrain.
TEST(ScanMatcher, PriorHoldsTheGuessAlongAHalfMappedCorridor) {
  const HalfMappedCorridor corridor;
  ScanMatcherParams params = TrackingMatcherParams();
  params.constraints.min_information_ratio = 0.0;
  const MatchResult held = corridor.Match(params);
  EXPECT_NEAR(held.pose.x(), corridor.truth.x(), 0.01);
  EXPECT_LT(std::abs(held.pose.y()), 0.5 * std::abs(corridor.guess.y()));
  params.prior_sigma_xy_m = 0.0;
  const MatchResult slid = corridor.Match(params);
  EXPECT_GT(std::abs(slid.pose.x() - corridor.truth.x()), 0.03) << "no drift: the test is moot";
}

// Without a prior, the constraint analysis finds the corridor's axis unconstrained and keeps the
// guess along it, while the match still corrects the offset across it.
TEST(ScanMatcher, KeepsTheGuessAlongAnUnconstrainedCorridor) {
  const HalfMappedCorridor corridor;
  ScanMatcherParams params;
  const MatchResult held = corridor.Match(params);
  EXPECT_EQ(held.constraints.unconstrained, 1);
  EXPECT_NEAR(held.pose.x(), corridor.truth.x(), 0.005);
  EXPECT_LT(std::abs(held.pose.y()), 0.5 * std::abs(corridor.guess.y()));
  params.constraints.min_information_ratio = 0.0;
  const MatchResult slid = corridor.Match(params);
  EXPECT_GT(std::abs(slid.pose.x() - corridor.truth.x()), 0.03) << "no drift: the test is moot";
}

// In the room every direction is constrained: the analysis changes nothing.
TEST(ScanMatcher, ConstraintAnalysisLeavesAWellConstrainedMatchAlone) {
  const OccupancyGrid grid = RoomMap();
  ScanMatcherParams params;
  ScanMatcherParams off = params;
  off.constraints.min_information_ratio = 0.0;
  for (const Pose2& truth : {Pose2(0.5, 0.3, 0.2), Pose2(-2.0, -1.0, -1.0)}) {
    const Pose2 guess = truth.Compose(Pose2(0.15, -0.1, 0.05));
    const MatchResult m =
        MatchScan(grid, PrepareScan(RoomScan(truth), 30.0, params), guess, params);
    const MatchResult m0 = MatchScan(grid, PrepareScan(RoomScan(truth), 30.0, off), guess, off);
    EXPECT_EQ(m.constraints.unconstrained, 0);
    EXPECT_EQ(m.pose.vector(), m0.pose.vector());
  }
}

// A second layer is read only where the map is unknown: an empty map over the room's layer
// scores as the room itself; the room over any layer scores as the room alone wherever the room
// is known; and the matcher climbs to the same pose through the layer.
TEST(ScanMatcher, SecondLayerFillsTheMapsUnknownCells) {
  const OccupancyGrid room = RoomMap();
  const OccupancyGrid empty;
  const ScanMatcherParams params;
  const Pose2 truth(0.5, 0.3, 0.2), guess(0.6, 0.25, 0.25);
  const ScanPoints points = PrepareScan(RoomScan(truth), 30.0, params);
  const MatchQuality alone = EvaluatePose(room, points, guess, params);
  const MatchQuality layered = EvaluatePose(GridMapView(empty, &room), points, guess, params);
  // The same cells; the map-only path reads them from the tile, the layered one cell by cell,
  // with the same arithmetic.
  EXPECT_EQ(layered.matched, alone.matched);
  EXPECT_EQ(layered.score, alone.score);
  EXPECT_EQ(layered.log_likelihood, alone.log_likelihood);
  EXPECT_EQ(EvaluatePose(GridMapView(room, &room), points, guess, params).score, alone.score);
  EXPECT_EQ(EvaluatePose(empty, points, guess, params).matched, 0);
  const MatchResult m = MatchScan(GridMapView(empty, &room), points, guess, params);
  const MatchResult m_alone = MatchScan(room, points, guess, params);
  EXPECT_TRUE(m.accepted);
  EXPECT_EQ(m.pose.x(), m_alone.pose.x());
  EXPECT_EQ(m.pose.y(), m_alone.pose.y());
  EXPECT_EQ(m.pose.theta(), m_alone.pose.theta());
}

// A guess whose heading is off by more than the climb recovers (a turn that odometry misjudged)
// ends in a poor local optimum; retried from other headings, the match finds the room again.
TEST(ScanMatcher, WidenedSearchRecoversAHeadingTheClimbCannot) {
  const OccupancyGrid grid = RoomMap();
  ScanMatcherParams params;
  const double offset = 0.5;  // the plain climb recovers up to about 0.45 rad here
  int recovered = 0, failed_plain = 0;
  for (const Pose2& truth : {Pose2(0.5, 0.3, 0.2), Pose2(-2.0, -1.0, -1.0), Pose2(2, 2.5, 2.5)}) {
    const ScanPoints points = PrepareScan(RoomScan(truth), 30.0, params);
    const Pose2 guess(truth.x(), truth.y(), truth.theta() + offset);
    params.widen_below_score_fraction = 0.0;
    const MatchResult plain = MatchScan(grid, points, guess, params);
    params.widen_below_score_fraction = 0.5;
    const MatchResult widened = MatchScan(grid, points, guess, params);
    EXPECT_GE(widened.quality.score, plain.quality.score);
    failed_plain += std::abs(WrapAngle(plain.pose.theta() - truth.theta())) > 0.02 ? 1 : 0;
    recovered += std::abs(WrapAngle(widened.pose.theta() - truth.theta())) < 0.01 ? 1 : 0;
  }
  EXPECT_EQ(recovered, 3);
  EXPECT_GE(failed_plain, 1) << "the plain climb recovers them all: the test is moot";
}

// The heading sweep scores the coarse pass at headings around the guess before climbing: the
// same misjudged turn is found at the cost of one coarse score per heading.
TEST(ScanMatcher, HeadingSweepRecoversAHeadingTheClimbCannot) {
  const OccupancyGrid grid = RoomMap();
  ScanMatcherParams params;
  const double offset = 0.5;
  int recovered = 0, failed_plain = 0;
  for (const Pose2& truth : {Pose2(0.5, 0.3, 0.2), Pose2(-2.0, -1.0, -1.0), Pose2(2, 2.5, 2.5)}) {
    const ScanPoints points = PrepareScan(RoomScan(truth), 30.0, params);
    const Pose2 guess(truth.x(), truth.y(), truth.theta() + offset);
    params.heading_sweep_rad = 0.0;
    const MatchResult plain = MatchScan(grid, points, guess, params);
    params.heading_sweep_rad = 0.6;
    const MatchResult swept = MatchScan(grid, points, guess, params);
    failed_plain += std::abs(WrapAngle(plain.pose.theta() - truth.theta())) > 0.02 ? 1 : 0;
    recovered += std::abs(WrapAngle(swept.pose.theta() - truth.theta())) < 0.01 ? 1 : 0;
  }
  EXPECT_EQ(recovered, 3);
  EXPECT_GE(failed_plain, 1) << "the plain climb recovers them all: the test is moot";
}

// A hall whose walls are 12–40 m from the robot, with columns along them, mapped from three scans
// a metre apart (as a sparse log's submap is). The next scan, a metre on, is matched from a
// guess 0.42 m and 0.03–0.1 rad off: its far returns land outside every beam's window, and the
// plain match often ends where it scores too little to be accepted. The rescue (range-scaled
// kernels, then the plain fine climb) finds those poses, and leaves accepted matches alone.
TEST(ScanMatcher, RescueMatchesAPoseAmongFarWallsThePlainMatchRejects) {
  FloorPlan hall;
  const auto box = [&](double x0, double y0, double x1, double y1) {
    hall.walls.push_back({{x0, y0}, {x1, y0}});
    hall.walls.push_back({{x1, y0}, {x1, y1}});
    hall.walls.push_back({{x1, y1}, {x0, y1}});
    hall.walls.push_back({{x0, y1}, {x0, y0}});
  };
  box(-40, -15, 30, 12);
  for (double x = -30; x <= 20; x += 10) box(x, 9, x + 1, 10);
  for (double x = -25; x <= 25; x += 10) box(x, -13, x + 1, -12);
  LaserSimParams laser;
  laser.range_limit_m = 50.0;
  laser.sigma_range_m = 0.03;
  Rng rng(3);
  ScanInsertionParams insertion;
  insertion.usable_range_m = 50.0;
  ScanMatcherParams params;
  int rejected = 0;
  for (double heading : {0.0, 0.5, 2.0, -1.0}) {
    for (double error_rad : {0.03, 0.06, 0.1}) {
      OccupancyGrid grid;
      const Pose2 start(-3.0, -1.0, heading);
      for (int k = 0; k < 3; ++k) {
        const Pose2 p = start.Compose(Pose2(k, 0, 0));
        InsertScan(grid, p, SimulateScan(hall, p, laser, rng), insertion);
      }
      const Pose2 truth = start.Compose(Pose2(3, 0, 0));
      const ScanPoints points = PrepareScan(SimulateScan(hall, truth, laser, rng), 50.0, params);
      const Pose2 guess = truth.Compose(Pose2(0.3, -0.3, error_rad));
      params.rescue_sigma_per_m = 0.0;
      const MatchResult plain = MatchScan(grid, points, guess, params);
      params.rescue_sigma_per_m = 0.02;
      const MatchResult rescued = MatchScan(grid, points, guess, params);
      EXPECT_TRUE(rescued.accepted);
      EXPECT_EQ(rescued.rescued, !plain.accepted);
      if (plain.accepted) {
        EXPECT_EQ(rescued.pose.vector(), plain.pose.vector());
        continue;
      }
      ++rejected;
      EXPECT_LT(std::abs(WrapAngle(rescued.pose.theta() - truth.theta())), 0.012);
      EXPECT_LT((rescued.pose.translation() - truth.translation()).norm(), 0.12);
    }
  }
  EXPECT_GE(rejected, 4) << "the plain match takes (nearly) all: the test is moot";
}

}  // namespace
}  // namespace slamkit
