#include <gtest/gtest.h>

#include <cmath>

#include "slamkit/core/angle.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/grid/match_constraints.hpp"

namespace slamkit {
namespace {

// Ends along a wall y = 1 (robot frame) every 5 cm with 1 cm noise, then a corner into x = 3.
std::vector<Eigen::Vector2d> WallThenCorner() {
  Rng rng(2);
  std::vector<Eigen::Vector2d> ends;
  for (int i = 0; i <= 40; ++i) ends.emplace_back(1.0 + 0.05 * i, 1.0 + rng.Normal(0.0, 0.01));
  for (int i = 1; i <= 20; ++i) ends.emplace_back(3.0 + rng.Normal(0.0, 0.01), 1.0 - 0.05 * i);
  return ends;
}

TEST(MatchConstraints, NormalsAreAcrossTheWallAndNoneAtTheCorner) {
  const std::vector<Eigen::Vector2d> ends = WallThenCorner();
  const std::vector<Eigen::Vector2d> n = EstimateNormals(ends, MatchConstraintParams{});
  ASSERT_EQ(n.size(), ends.size());
  for (int i = 0; i <= 30; ++i) {  // on the first wall, away from the corner
    EXPECT_NEAR(n[i].norm(), 1.0, 1e-9) << i;
    EXPECT_GT(std::abs(n[i].y()), std::cos(0.1)) << i;
  }
  EXPECT_TRUE(n[40].isZero()) << "the corner has no line through its neighbours";
  for (int i = 50; i <= 60; ++i) EXPECT_GT(std::abs(n[i].x()), std::cos(0.1)) << i;
}

// Both walls of a corridor along x: the information across it and in heading is large, along it
// nearly nothing, so exactly one direction (x) is unconstrained; a wall across the corridor
// constrains it again.
TEST(MatchConstraints, ACorridorLeavesOnlyItsAxisUnconstrained) {
  Rng rng(4);
  std::vector<Eigen::Vector2d> ends;
  for (double y : {-1.0, 1.0}) {
    for (int i = 0; i < 80; ++i) ends.emplace_back(0.1 * i - 2.0, y + rng.Normal(0.0, 0.01));
  }
  const MatchConstraintParams params;
  std::vector<std::uint8_t> hits(ends.size(), 1);
  auto normals = EstimateNormals(ends, params);
  const MatchConstraints corridor =
      FindConstraints(ComputeMatchInformation(ends, normals, hits), params);
  ASSERT_EQ(corridor.unconstrained, 1);
  // keep removes a shift along x and leaves one across it, and a turn, as they are.
  EXPECT_LT((corridor.keep * Eigen::Vector3d(1, 0, 0)).norm(), 0.05);
  EXPECT_NEAR((corridor.keep * Eigen::Vector3d(0, 1, 0)).y(), 1.0, 0.05);
  EXPECT_NEAR((corridor.keep * Eigen::Vector3d(0, 0, 1)).z(), 1.0, 0.05);

  for (int i = 0; i < 20; ++i) ends.emplace_back(6.0 + rng.Normal(0.0, 0.01), 0.1 * i - 0.95);
  hits.assign(ends.size(), 1);
  normals = EstimateNormals(ends, params);
  EXPECT_EQ(FindConstraints(ComputeMatchInformation(ends, normals, hits), params).unconstrained, 0);
  // Beams that found no wall in the map give no information: without the end wall's hits the
  // corridor is open again.
  for (std::size_t i = 160; i < ends.size(); ++i) hits[i] = 0;
  EXPECT_EQ(FindConstraints(ComputeMatchInformation(ends, normals, hits), params).unconstrained, 1);
}

TEST(MatchConstraints, KeepGuessAlongTakesBackOnlyTheUnconstrainedMove) {
  MatchConstraints c;
  c.keep = Eigen::Vector3d(0.0, 1.0, 1.0).asDiagonal();  // robot-frame x unconstrained
  c.unconstrained = 1;
  const Pose2 initial(1.0, 2.0, M_PI / 2);  // robot x points along world y
  const Pose2 match(1.1, 2.3, M_PI / 2 + 0.02);
  const Pose2 kept = KeepGuessAlong(initial, match, c);
  EXPECT_NEAR(kept.y(), initial.y(), 1e-12);  // along the robot's x: back to the guess
  EXPECT_NEAR(kept.x(), match.x(), 1e-12);    // across it: the match
  EXPECT_NEAR(WrapAngle(kept.theta() - match.theta()), 0.0, 1e-12);
  c.unconstrained = 0;
  c.keep.setIdentity();
  EXPECT_EQ(KeepGuessAlong(initial, match, c).vector(), match.vector());
}

}  // namespace
}  // namespace slamkit
