#include "slamkit/filters/graph/correlative_matcher.hpp"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"

namespace slamkit::correlative_matcher_test {
namespace {

constexpr double kRes = 0.05;

// A 12 m × 12 m map of random wall segments, free elsewhere: what a finished submap looks like.
OccupancyGrid RandomMap(Rng& rng) {
  OccupancyGrid map(OccupancyGridParams{kRes});
  for (int y = 0; y < 240; ++y) {
    for (int x = 0; x < 240; ++x) map.Update({x, y}, -1.0f);
  }
  for (int k = 0; k < 14; ++k) {
    const Eigen::Vector2d a(rng.Uniform(0.5, 11.5), rng.Uniform(0.5, 11.5));
    const double angle = rng.Uniform(-M_PI, M_PI), length = rng.Uniform(1.0, 4.0);
    for (double t = 0.0; t <= length; t += kRes / 2) {
      const Eigen::Vector2d p = a + t * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      const CellIndex c = map.WorldToCell(p);
      if (c.x >= 0 && c.y >= 0 && c.x < 240 && c.y < 240) map.Update(c, 4.0f - map.LogOdds(c));
    }
  }
  return map;
}

// The occupied cells within 5 m of `pose`, seen from it, jittered inside their cells.
std::vector<Eigen::Vector2d> ScanOf(const OccupancyGrid& map, const Pose2& pose, Rng& rng) {
  std::vector<Eigen::Vector2d> points;
  for (int y = 0; y < 240; ++y) {
    for (int x = 0; x < 240; ++x) {
      if (map.Probability({x, y}) < 0.9) continue;
      const Eigen::Vector2d c = map.CellCenter({x, y}) +
                                Eigen::Vector2d(rng.Uniform(-0.01, 0.01), rng.Uniform(-0.01, 0.01));
      if ((c - pose.translation()).norm() < 5.0) points.push_back(pose.TransformTo(c));
    }
  }
  return points;
}

// Branch and bound finds the exhaustive search's best score on every random map, and its pose
// when that best is unique, scoring far fewer candidates; both find the true pose.
TEST(CorrelativeMatcher, BranchAndBoundEqualsTheExhaustiveSearch) {
  Rng rng(4);
  CorrelativeMatcherParams params;
  params.linear_window_m = 0.6;
  params.angular_window_rad = 0.1;
  params.branch_and_bound_depth = 4;
  params.min_score = 0.3;
  for (int trial = 0; trial < 8; ++trial) {
    const OccupancyGrid map = RandomMap(rng);
    const Pose2 truth(rng.Uniform(4, 8), rng.Uniform(4, 8), rng.Uniform(-3, 3));
    const std::vector<Eigen::Vector2d> scan = ScanOf(map, truth, rng);
    ASSERT_GT(scan.size(), 50u);
    const Pose2 initial(truth.x() + rng.Uniform(-0.4, 0.4), truth.y() + rng.Uniform(-0.4, 0.4),
                        truth.theta() + rng.Uniform(-0.06, 0.06));
    const CorrelativeMatcher matcher(map, params);
    const std::optional<CorrelativeMatch> full = matcher.Exhaustive(scan, initial);
    long scored = 0;
    const std::optional<CorrelativeMatch> fast = matcher.BranchAndBound(scan, initial, {}, &scored);
    ASSERT_TRUE(full.has_value() && fast.has_value()) << trial;
    EXPECT_EQ(fast->score, full->score) << trial;
    EXPECT_EQ(fast->pose.vector(), full->pose.vector()) << trial;
    // The score is the mean occupancy of the map at the points' cells (each to 1/65535: the
    // matcher holds probabilities in 16 bits).
    double mean = 0.0;
    for (const Eigen::Vector2d& p : scan) {
      const CellIndex c = map.WorldToCell(full->pose.TransformFrom(p));
      mean += map.IsKnown(c) ? map.Probability(c) : 0.0;
    }
    EXPECT_NEAR(full->score, mean / double(scan.size()), 1.0 / 65535) << trial;
    EXPECT_GT(full->score, 0.7) << trial;  // the angle grid misses the true heading slightly
    EXPECT_LT((full->pose.translation() - truth.translation()).norm(), 2.0 * kRes) << trial;
    EXPECT_LT(std::abs(full->pose.theta() - truth.theta()), 0.02) << trial;
    const long exhaustive = long(std::pow(2 * std::ceil(0.6 / kRes) + 1, 2)) * 9;
    EXPECT_LT(scored, exhaustive / 3) << trial;
  }
}

TEST(CorrelativeMatcher, NoMatchBelowTheMinimumScoreAndBadParams) {
  Rng rng(6);
  const OccupancyGrid map = RandomMap(rng);
  CorrelativeMatcherParams params;
  params.linear_window_m = 0.3;
  params.min_score = 0.99;
  const CorrelativeMatcher matcher(map, params);
  // Points in free space only.
  const std::vector<Eigen::Vector2d> nowhere = {{0.1, 0.0}, {0.0, 0.1}};
  EXPECT_FALSE(matcher.BranchAndBound(nowhere, Pose2(-50, -50, 0)).has_value());
  EXPECT_FALSE(matcher.Exhaustive(nowhere, Pose2(-50, -50, 0)).has_value());
  EXPECT_FALSE(matcher.BranchAndBound({}, Pose2()).has_value());
  params.branch_and_bound_depth = 0;
  EXPECT_THROW(CorrelativeMatcher(map, params), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit::correlative_matcher_test
