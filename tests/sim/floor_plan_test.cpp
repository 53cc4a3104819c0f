#include "slamkit/sim/floor_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "common/synthetic_room.hpp"
#include "slamkit/core/rng.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

constexpr double kFar_m = 100.0;

Eigen::Vector2d Direction(double angle_rad) { return {std::cos(angle_rad), std::sin(angle_rad)}; }

// The plan with 64 short walls added far away, so that CastRay takes the bucket-grid path.
FloorPlan WithFarClutter(const FloorPlan& plan) {
  FloorPlan cluttered{plan.walls};
  for (int i = 0; i < 64; ++i) {
    const Eigen::Vector2d a(60.0 + i % 8, 60.0 + i / 8);
    cluttered.walls.push_back({a, a + Eigen::Vector2d(0.5, 0.25)});
  }
  return cluttered;
}

// Checks CastRay on the plan as given (brute force: few walls) and with far clutter (bucket grid).
void ExpectCast(const FloorPlan& plan, const Eigen::Vector2d& origin, double angle_rad,
                double expected_m, double max_range_m = kFar_m) {
  const Eigen::Vector2d d = Direction(angle_rad);
  ASSERT_LT(plan.walls.size(), 64u);
  EXPECT_NEAR(CastRay(plan, origin, d, max_range_m), expected_m, 1e-9)
      << "brute force from " << origin.transpose() << " at " << angle_rad;
  EXPECT_NEAR(CastRay(WithFarClutter(plan), origin, d, max_range_m), expected_m, 1e-9)
      << "grid from " << origin.transpose() << " at " << angle_rad;
}

// The room of tests/common: [-8, 8] × [-5, 5] with pillars [-3, -2] × [1, 2.5] and
// [3, 4.5] × [-2.5, -1.5].
TEST(CastRay, AxisAlignedWalls) {
  const FloorPlan room{testing::RoomWalls()};
  ExpectCast(room, {0.0, 0.0}, 0.0, 8.0);
  ExpectCast(room, {0.0, 0.0}, std::numbers::pi / 2, 5.0);
  ExpectCast(room, {0.0, 0.0}, std::numbers::pi, 8.0);
  ExpectCast(room, {0.0, -2.0}, 0.0, 3.0);   // the left face of the second pillar
  ExpectCast(room, {0.0, 1.5}, std::numbers::pi, 2.0);  // the right face of the first
  ExpectCast(room, {0.0, 0.0}, std::atan2(4.0, 3.0), 6.25);  // oblique ray, top wall
  ExpectCast(room, {0.0, 0.0}, std::numbers::pi / 4, 5.0 * std::sqrt(2.0));
}

TEST(CastRay, ObliqueWallAndNoHit) {
  const FloorPlan plan{{{{2.0, -1.0}, {0.0, 1.0}}}};  // on the line x + y = 1
  ExpectCast(plan, {0.0, 0.0}, std::numbers::pi / 4, std::sqrt(0.5));
  ExpectCast(plan, {0.0, 0.0}, 0.0, 1.0);
  ExpectCast(plan, {1.5, -2.0}, std::numbers::pi / 2, 1.5);
  ExpectCast(plan, {0.0, 0.0}, std::numbers::pi, kFar_m);  // nothing behind
  ExpectCast(plan, {0.0, 0.0}, 0.0, 0.75, 0.75);           // wall beyond the range
  ExpectCast(plan, {3.0, 0.0}, std::numbers::pi, 2.0);     // from the far side
  ExpectCast(plan, {3.0, -2.0}, 3 * std::numbers::pi / 4, kFar_m);  // edge-on, along the wall
}

TEST(CastRay, GrazingACorner) {
  const FloorPlan room{testing::RoomWalls()};
  // The line y = x − 4.5 touches the second pillar only at its corner (3, −1.5).
  const double diagonal = std::numbers::pi / 4;
  ExpectCast(room, {1.0, -3.5}, diagonal, 2.0 * std::sqrt(2.0));
  // A micrometre above, the ray passes the corner and reaches the right wall at (8, 3.5).
  ExpectCast(room, {1.0, -3.5 + 1e-6}, diagonal, 7.0 * std::sqrt(2.0));
  // A micrometre below, it hits the pillar's left face just under the corner.
  ExpectCast(room, {1.0, -3.5 - 1e-6}, diagonal, 2.0 * std::sqrt(2.0));
}

// Walls in [0, 50]², a third of them axis-aligned with whole-metre end points so that many lie
// on the grid's cell boundaries.
FloorPlan RandomPlan(int count, Rng& rng) {
  FloorPlan plan;
  for (int i = 0; i < count; ++i) {
    if (i % 3 == 0) {
      const Eigen::Vector2d a = testing::UniformVector2(rng, 0, 50, 0, 50).array().floor();
      const double length = std::floor(rng.Uniform(1, 6));
      const Eigen::Vector2d along = i % 2 ? Eigen::Vector2d(length, 0) : Eigen::Vector2d(0, length);
      plan.walls.push_back({a, a + along});
    } else {
      const Eigen::Vector2d a = testing::UniformVector2(rng, 0, 50, 0, 50);
      const double angle = rng.Uniform(-4, 4);  // drawn before the length, as GCC did
      plan.walls.push_back({a, a + rng.Uniform(0.1, 8.0) * Direction(angle)});
    }
  }
  return plan;
}

TEST(CastRay, GridEqualsBruteForceOnRandomPlan) {
  Rng rng(11);
  const FloorPlan plan = RandomPlan(500, rng);
  int mismatches = 0;
  for (int i = 0; i < 10000; ++i) {
    Eigen::Vector2d origin = testing::UniformVector2(rng, -10, 60, -10, 60);
    if (i % 4 == 0) origin = origin.array().floor();  // on cell corners
    // Every fifth ray is axis-aligned: it runs along cell boundaries and walls.
    const double angle = i % 5 == 0 ? (i / 5 % 4) * std::numbers::pi / 2 : rng.Uniform(-4, 4);
    const Eigen::Vector2d d = i % 5 == 0 ? Eigen::Vector2d(std::round(std::cos(angle)),
                                                           std::round(std::sin(angle)))
                                         : Direction(angle);
    const double max_range = rng.Uniform(1.0, 100.0);
    const double grid = CastRay(plan, origin, d, max_range);
    const double brute = CastRayBruteForce(plan, origin, d, max_range);
    if (grid != brute && ++mismatches <= 5) {
      ADD_FAILURE() << "ray " << i << " from " << origin.transpose() << " along " << d.transpose()
                    << ": grid " << grid << ", brute force " << brute;
    }
  }
  EXPECT_EQ(mismatches, 0);
}

// A wall that only touches a cell corner, hit by diagonal rays through that corner: the walk steps
// into only three of the four cells around the corner, and must still find the wall.
TEST(CastRay, GridFindsWallsEndingAtACellCorner) {
  const Eigen::Vector2d corner(5.0, 5.0);  // a cell corner: the grid starts at (0, 0), 1 m cells
  for (int quadrant = 0; quadrant < 4; ++quadrant) {
    FloorPlan plan = WithFarClutter(FloorPlan{{{{0.0, 0.0}, {0.1, 0.0}}}});
    const double wall_angle = (quadrant + 0.3) * std::numbers::pi / 2;
    plan.walls.push_back({corner, corner + 0.4 * Direction(wall_angle)});
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d d = Direction((2 * k + 1) * std::numbers::pi / 4);
      const Eigen::Vector2d origin = corner - 2.0 * d.array().sign().matrix();
      const double brute = CastRayBruteForce(plan, origin, d, kFar_m);
      SCOPED_TRACE(::testing::Message() << "quadrant " << quadrant << ", ray " << k);
      EXPECT_NEAR(brute, 2.0 * std::sqrt(2.0), 1e-9);
      EXPECT_EQ(CastRay(plan, origin, d, kFar_m), brute);
    }
  }
}

TEST(CastRay, IndexFollowsEditedWalls) {
  Rng rng(3);
  FloorPlan plan = RandomPlan(100, rng);
  const Eigen::Vector2d origin(-20.0, -20.0);
  const Eigen::Vector2d away(-1.0, 0.0);  // every wall is to the right
  EXPECT_EQ(CastRay(plan, origin, away, kFar_m), kFar_m);
  const FloorPlan copy = plan;
  plan.walls.push_back({{-22.0, -30.0}, {-22.0, -10.0}});  // a new size: the index is rebuilt
  EXPECT_NEAR(CastRay(plan, origin, away, kFar_m), 2.0, 1e-12);
  EXPECT_EQ(CastRay(copy, origin, away, kFar_m), kFar_m);  // the copy keeps its own walls
  plan.walls.back() = {{-21.0, -30.0}, {-21.0, -10.0}};    // in place: Reset() is needed
  plan.ray_index.Reset();
  EXPECT_NEAR(CastRay(plan, origin, away, kFar_m), 1.0, 1e-12);
}

// The default maze: corridor centre lines at 1.1, 6.8, 12.5, 18.2 and 23.9 m; blocks start at
// 2.2, 7.9, 13.6 and 19.3 m.
TEST(SquareMaze, OuterWallAndLayout) {
  const FloorPlan maze = MakeSquareMaze();
  ASSERT_EQ(maze.walls.size(), 4u + 16u * 4u);
  Eigen::Vector2d lo = maze.walls[0].first, hi = lo;
  for (const auto& [a, b] : maze.walls) {
    lo = lo.cwiseMin(a).cwiseMin(b);
    hi = hi.cwiseMax(a).cwiseMax(b);
  }
  EXPECT_TRUE(lo.isApprox(Eigen::Vector2d(0, 0)));
  EXPECT_TRUE(hi.isApprox(Eigen::Vector2d(25, 25)));
  for (int k = 0; k < 5; ++k) {  // each corridor, both ways, runs wall to wall
    const double c = 1.1 + 5.7 * k;
    EXPECT_NEAR(CastRay(maze, {0.5, c}, {1, 0}, kFar_m), 24.5, 1e-9) << "row " << k;
    EXPECT_NEAR(CastRay(maze, {c, 0.5}, {0, 1}, kFar_m), 24.5, 1e-9) << "column " << k;
    EXPECT_NEAR(CastRay(maze, {24.5, c}, {-1, 0}, kFar_m), 24.5, 1e-9) << "row " << k;
  }
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 4; ++i) {  // from inside each block to its faces, then from corridors
      const Eigen::Vector2d centre(3.95 + 5.7 * i, 3.95 + 5.7 * j);
      EXPECT_NEAR(CastRay(maze, centre, {1, 0}, kFar_m), 1.75, 1e-9);
      EXPECT_NEAR(CastRay(maze, centre, {0, -1}, kFar_m), 1.75, 1e-9);
      EXPECT_NEAR(CastRay(maze, centre - Eigen::Vector2d(2.85, 0), {1, 0}, kFar_m), 1.1, 1e-9);
      EXPECT_NEAR(CastRay(maze, centre + Eigen::Vector2d(0, 2.85), {0, -1}, kFar_m), 1.1, 1e-9);
    }
  }
  // From a corridor crossing, diagonally into the corner of the next block.
  EXPECT_NEAR(CastRay(maze, {12.5, 12.5}, Direction(std::numbers::pi / 4), kFar_m),
              1.1 * std::sqrt(2.0), 1e-9);
}

TEST(SquareMaze, OtherSizesCentreTheBlocks) {
  SquareMazeParams params;
  params.outer_size_m = 21.0;
  params.block_size_m = 4.0;
  params.corridor_width_m = 2.0;
  params.origin_m = {-10.0, 5.0};
  const FloorPlan maze = MakeSquareMaze(params);  // 3 × 3 blocks with 2.5 m outer corridors
  ASSERT_EQ(maze.walls.size(), 4u + 9u * 4u);
  EXPECT_NEAR(CastRay(maze, {-10.0 + 1.0, 5.0 + 4.5}, {1, 0}, kFar_m), 1.5, 1e-9);
  EXPECT_NEAR(CastRay(maze, {-10.0 + 6.9, 5.0 + 4.5}, {1, 0}, kFar_m), 1.6, 1e-9);
  params.block_size_m = -1.0;
  EXPECT_THROW(MakeSquareMaze(params), std::invalid_argument);
}

using SegmentKey = std::array<double, 4>;

// The walls as sorted (x0, y0, x1, y1) with each wall's lesser end first.
std::vector<SegmentKey> Keys(const FloorPlan& plan) {
  std::vector<SegmentKey> keys;
  for (auto [a, b] : plan.walls) {
    if (std::make_pair(b.x(), b.y()) < std::make_pair(a.x(), a.y())) std::swap(a, b);
    keys.push_back({a.x(), a.y(), b.x(), b.y()});
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

TEST(FloorPlanFromOccupancy, SinglePixelGivesFourEdges) {
  OccupancyImage image;
  image.width = 3;
  image.height = 3;
  image.pixels = {254, 254, 254, 254, 0, 254, 254, 254, 254};
  image.resolution_m = 0.5;
  image.origin_m = {-1.0, 2.0};
  const std::vector<SegmentKey> expected = {
      {-0.5, 2.5, -0.5, 3.0}, {-0.5, 2.5, 0.0, 2.5}, {-0.5, 3.0, 0.0, 3.0}, {0.0, 2.5, 0.0, 3.0}};
  EXPECT_EQ(Keys(FloorPlanFromOccupancy(image)), expected);
}

TEST(FloorPlanFromOccupancy, MergesCollinearEdgesAndReadsTopRowFirst) {
  OccupancyImage image;  // top row: X . ; bottom row: X X (an L)
  image.width = 2;
  image.height = 2;
  image.pixels = {0, 255, 100, 127};  // below the default 128: occupied
  image.resolution_m = 1.0;
  const std::vector<SegmentKey> expected = {{0, 0, 0, 2}, {0, 0, 2, 0}, {0, 2, 1, 2},
                                            {1, 1, 1, 2}, {1, 1, 2, 1}, {2, 0, 2, 1}};
  EXPECT_EQ(Keys(FloorPlanFromOccupancy(image)), expected);
  // With the threshold at 127 the bottom-right pixel is free: a 1 × 2 column remains.
  const std::vector<SegmentKey> column = {{0, 0, 0, 2}, {0, 0, 1, 0}, {0, 2, 1, 2}, {1, 0, 1, 2}};
  EXPECT_EQ(Keys(FloorPlanFromOccupancy(image, 127)), column);
}

TEST(FloorPlanFromOccupancy, SolidBlockIsFourLongWallsAndStopsRays) {
  OccupancyImage image;
  image.width = 40;
  image.height = 30;
  image.pixels.assign(40 * 30, 0);
  image.resolution_m = 0.1;
  image.origin_m = {1.0, 1.0};
  const FloorPlan plan = FloorPlanFromOccupancy(image);
  const std::vector<SegmentKey> expected = {{1, 1, 1, 4}, {1, 1, 5, 1}, {1, 4, 5, 4}, {5, 1, 5, 4}};
  const std::vector<SegmentKey> keys = Keys(plan);
  ASSERT_EQ(keys.size(), expected.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(keys[i][k], expected[i][k], 1e-12);
  }
  EXPECT_NEAR(CastRay(plan, {0.0, 2.0}, {1, 0}, kFar_m), 1.0, 1e-12);
  image.pixels.pop_back();
  EXPECT_THROW(FloorPlanFromOccupancy(image), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
