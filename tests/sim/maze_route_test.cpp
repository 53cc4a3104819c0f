#include "slamkit/sim/maze_route.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "slamkit/models/line_sensor.hpp"
#include "slamkit/sim/laser_sim.hpp"

namespace slamkit {
namespace {

double PointToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                      const Eigen::Vector2d& b) {
  return std::sqrt(PointSegmentDistanceSq(p, a, b));
}

double Cross(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return u.x() * v.y() - u.y() * v.x();
}

// Distance between two closed segments: 0 when they cross, else the least end-to-segment distance.
double SegmentToSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                        const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  const double d1 = Cross(b - a, c - a), d2 = Cross(b - a, d - a);
  const double d3 = Cross(d - c, a - c), d4 = Cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return 0.0;
  }
  return std::min({PointToSegment(a, c, d), PointToSegment(b, c, d), PointToSegment(c, a, b),
                   PointToSegment(d, a, b)});
}

double ClearanceOfPoint(const FloorPlan& plan, const Eigen::Vector2d& p) {
  double least = std::numeric_limits<double>::infinity();
  for (const auto& [a, b] : plan.walls) least = std::min(least, PointToSegment(p, a, b));
  return least;
}

// The legs of the closed route: waypoint i to i + 1, and the last one back to the first.
std::vector<WallSegment> Legs(const RouteParams& route) {
  std::vector<WallSegment> legs;
  const auto& w = route.waypoints_m;
  for (std::size_t i = 0; i < w.size(); ++i) legs.push_back({w[i], w[(i + 1) % w.size()]});
  return legs;
}

void ExpectLegsClearOfWalls(const SquareMazeParams& params, double min_clearance_m) {
  const FloorPlan maze = MakeSquareMaze(params);
  const RouteParams route = MazeRoute(params);
  for (const WallSegment& leg : Legs(route)) {
    double least = std::numeric_limits<double>::infinity();
    for (const auto& [a, b] : maze.walls) {
      least = std::min(least, SegmentToSegment(leg.first, leg.second, a, b));
    }
    EXPECT_GE(least, min_clearance_m) << "leg from " << leg.first.transpose() << " to "
                                      << leg.second.transpose();
  }
}

TEST(MazeRoute, CorridorCentresOfTheDefaultMaze) {
  const std::vector<double> centres = SquareMazeCorridorCentres();
  const std::vector<double> expected = {1.1, 6.8, 12.5, 18.2, 23.9};
  ASSERT_EQ(centres.size(), expected.size());
  for (std::size_t i = 0; i < centres.size(); ++i) EXPECT_NEAR(centres[i], expected[i], 1e-12);
}

// Every waypoint and every straight leg between consecutive ones (the closing leg included)
// stays at least 0.5 m from every wall: on a corridor centre line, 1.1 m.
TEST(MazeRoute, WaypointsAndLegsKeepOffTheWalls) {
  const FloorPlan maze = MakeSquareMaze();
  for (const Eigen::Vector2d& w : MazeRoute().waypoints_m) {
    EXPECT_GE(ClearanceOfPoint(maze, w), 1.1 - 1e-9) << w.transpose();
  }
  ExpectLegsClearOfWalls({}, 1.1 - 1e-9);
  // 3 × 3 blocks with 2.5 m outer corridors (an even number of corridor lines), moved away from
  // the world origin.
  ExpectLegsClearOfWalls({.outer_size_m = 20.0, .block_size_m = 3.5, .corridor_width_m = 2.0,
                          .origin_m = Eigen::Vector2d(-3.0, 7.0)},
                         1.0 - 1e-9);
  ExpectLegsClearOfWalls({.outer_size_m = 10.0, .block_size_m = 4.0, .corridor_width_m = 2.0},
                         1.0 - 1e-9);  // one block
}

// Each stretch of corridor between two neighbouring crossings lies on some leg.
TEST(MazeRoute, DrivesEveryCorridor) {
  for (const SquareMazeParams& params :
       {SquareMazeParams{}, SquareMazeParams{.outer_size_m = 20.0, .corridor_width_m = 2.0}}) {
    const std::vector<double> c = SquareMazeCorridorCentres(params);
    const std::vector<WallSegment> legs = Legs(MazeRoute(params));
    auto on_a_leg = [&](const Eigen::Vector2d& p) {
      return std::any_of(legs.begin(), legs.end(), [&](const WallSegment& leg) {
        return PointToSegment(p, leg.first, leg.second) < 1e-9;
      });
    };
    for (std::size_t i = 0; i < c.size(); ++i) {
      for (std::size_t j = 0; j + 1 < c.size(); ++j) {
        const double mid = 0.5 * (c[j] + c[j + 1]);
        EXPECT_TRUE(on_a_leg(params.origin_m + Eigen::Vector2d(c[i], mid))) << i << " " << j;
        EXPECT_TRUE(on_a_leg(params.origin_m + Eigen::Vector2d(mid, c[i]))) << i << " " << j;
      }
    }
  }
}

// The robot driving the route (default speed and controller) completes it and keeps off the
// walls on its true path, corners included (0.5 m turn radius, 0.25 m switch distance).
TEST(MazeRoute, DrivenPathCompletesAndKeepsOffTheWalls) {
  const FloorPlan maze = MakeSquareMaze();
  GridSimParams params;
  params.route = MazeRoute();
  params.laser.beams = 1;  // the scans do not matter here
  params.sigma_v_mps = 0.0;
  params.sigma_omega_radps = 0.0;
  const Pose2 start = RouteStartPose(params.route);
  Rng rng(3);
  const GridSimRun run = SimulateGridRun(maze, params, start, rng);
  // 10 legs of 22.8 m and 8 of 5.7 m at 0.5 m/s: 547 s.
  EXPECT_GT(run.truth.size(), 5300u);
  EXPECT_LT(run.truth.size(), 5550u);  // 5491 measured: each turn overshoots a little
  EXPECT_LT((run.truth.back().pose.translation() - start.translation()).norm(), 0.3);
  double least = std::numeric_limits<double>::infinity();
  for (const StampedPose& p : run.truth) {
    least = std::min(least, ClearanceOfPoint(maze, p.pose.translation()));
  }
  EXPECT_GE(least, 0.5);
}

TEST(MazeRoute, StartPoseFacesTheSecondWaypoint) {
  const RouteParams route = MazeRoute();
  const Pose2 start = RouteStartPose(route);
  EXPECT_NEAR(start.x(), 1.1, 1e-12);
  EXPECT_NEAR(start.y(), 1.1, 1e-12);
  EXPECT_NEAR(start.theta(), 0.0, 1e-12);
  RouteParams north;
  north.waypoints_m = {{1.0, 1.0}, {1.0, 5.0}};
  EXPECT_NEAR(RouteStartPose(north).theta(), std::numbers::pi / 2, 1e-12);
  EXPECT_THROW(RouteStartPose(RouteParams{}), std::invalid_argument);
}

TEST(MazeRoute, MazeWithoutBlocksThrows) {
  EXPECT_THROW(MazeRoute({.outer_size_m = 3.0}), std::invalid_argument);
  EXPECT_THROW(MazeRoute({.block_size_m = -1.0}), std::invalid_argument);
  EXPECT_TRUE(SquareMazeCorridorCentres({.outer_size_m = 3.0}).empty());
}

}  // namespace
}  // namespace slamkit
