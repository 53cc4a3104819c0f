#include "slamkit/planning/frontiers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace slamkit {
namespace {

// The seed's laser: 181 beams over 180°, 1° apart (beam 90 looks straight ahead).
LaserScan SickScan(float range_m) {
  LaserScan scan;
  scan.angle_min_rad = -M_PI / 2.0;
  scan.angle_increment_rad = M_PI / 180.0;
  scan.max_range_m = 30.0;
  scan.ranges_m.assign(181, range_m);
  return scan;
}

void Open(LaserScan* scan, int first, int last, float range_m) {
  for (int i = first; i <= last; ++i) scan->ranges_m[i] = range_m;
}

TEST(FindFrontiers, AnOpeningGivesOnePointOnItsMiddleBeam) {
  LaserScan scan = SickScan(3.0f);
  Open(&scan, 110, 130, 30.0f);  // no return, 20°..40° to the left
  const Pose2 robot(1.0, 2.0, 0.5);
  const std::vector<Frontier> f = FindFrontiers(scan, robot, {.goal_distance_m = 4.0});
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].first_beam, 110);
  EXPECT_EQ(f[0].last_beam, 130);
  const double bearing = 30.0 * M_PI / 180.0;
  EXPECT_NEAR(f[0].bearing_rad, bearing, 1e-9);
  const Eigen::Vector2d expected = robot.TransformFrom(4.0 * Eigen::Vector2d(std::cos(bearing),
                                                                            std::sin(bearing)));
  EXPECT_LT((f[0].point_world_m - expected).norm(), 1e-9);
  // The returns at 19° and 41° on its two sides, 3 m away, are 2 · 3 · sin(11°) apart.
  EXPECT_NEAR(f[0].width_m, 6.0 * std::sin(11.0 * M_PI / 180.0), 1e-4);
}

TEST(FindFrontiers, ReadingsBeyondTheOpenRangeAreOpenAndInvalidOnesAreNot) {
  LaserScan scan = SickScan(3.0f);
  Open(&scan, 20, 40, 12.0f);  // returns, but beyond the 10 m the filter uses
  Open(&scan, 140, 160, std::numeric_limits<float>::quiet_NaN());
  const std::vector<Frontier> f = FindFrontiers(scan, Pose2(), {.open_range_m = 10.0});
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].first_beam, 20);
}

TEST(FindFrontiers, OpeningsTooNarrowForTheRobotAreNotFrontiers) {
  LaserScan scan = SickScan(3.0f);
  Open(&scan, 60, 66, 30.0f);  // 7 beams; the returns beside it are 2 · 3 · sin(4°) = 0.42 m apart
  Open(&scan, 100, 101, 30.0f);  // too few beams
  EXPECT_TRUE(FindFrontiers(scan, Pose2(), {.min_width_m = 0.6}).empty());
  EXPECT_EQ(FindFrontiers(scan, Pose2(), {.min_width_m = 0.4}).size(), 1u);
}

TEST(FindFrontiers, AScanThatSeesWallsEverywhereHasNone) {
  EXPECT_TRUE(FindFrontiers(SickScan(5.0f), Pose2()).empty());
  const std::vector<Frontier> all_open = FindFrontiers(SickScan(30.0f), Pose2());
  ASSERT_EQ(all_open.size(), 1u);
  EXPECT_NEAR(all_open[0].bearing_rad, 0.0, 1e-9);
}

TEST(FindFrontiers, TheLaserOffsetMovesThePoints) {
  LaserScan scan = SickScan(3.0f);
  Open(&scan, 80, 100, 30.0f);
  scan.laser_offset = Pose2(0.5, 0.0, M_PI / 2.0);  // mounted 0.5 m ahead, looking left
  const std::vector<Frontier> f = FindFrontiers(scan, Pose2(), {.goal_distance_m = 4.0});
  ASSERT_EQ(f.size(), 1u);
  EXPECT_LT((f[0].point_world_m - Eigen::Vector2d(0.5, 4.0)).norm(), 1e-9);
  EXPECT_NEAR(f[0].bearing_rad, std::atan2(4.0, 0.5), 1e-9);
}

Frontier At(double x, double y, double bearing) {
  return {.point_world_m = {x, y}, .bearing_rad = bearing};
}

TEST(ChooseFrontier, TheLeastTurnAmongThoseNotVisited) {
  const std::vector<Frontier> f = {At(5, 5, 0.8), At(4, 0, 0.1), At(0, 4, -0.3)};
  EXPECT_EQ(ChooseFrontier(f, {})->point_world_m, Eigen::Vector2d(4, 0));
  const std::vector<Eigen::Vector2d> visited = {{4.5, 0.5}};
  EXPECT_EQ(ChooseFrontier(f, visited, {.revisit_radius_m = 1.0})->point_world_m,
            Eigen::Vector2d(0, 4));
  const std::vector<Eigen::Vector2d> everywhere = {{5, 5}, {4, 0}, {0, 4}};
  EXPECT_FALSE(ChooseFrontier(f, everywhere).has_value());
}

}  // namespace
}  // namespace slamkit
