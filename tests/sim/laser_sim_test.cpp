#include "slamkit/sim/laser_sim.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "common/synthetic_room.hpp"

namespace slamkit {
namespace {

constexpr double kPi = std::numbers::pi;

LaserSimParams NoiseFree() {
  LaserSimParams params;
  params.sigma_range_m = 0.0;
  return params;
}

TEST(SimulateScan, EqualsCastRayWithoutNoise) {
  const FloorPlan maze = MakeSquareMaze();
  LaserSimParams params = NoiseFree();
  params.laser_offset = Pose2(0.2, 0.05, 0.1);
  params.range_limit_m = 15.0;  // some beams see farther: those must read as no-returns
  const Pose2 robot(6.8, 12.5, 0.3);
  Rng rng(1);
  const LaserScan scan = SimulateScan(maze, robot, params, rng);
  ASSERT_EQ(scan.ranges_m.size(), 180u);
  EXPECT_EQ(scan.max_range_m, params.max_range_m);
  EXPECT_TRUE(scan.laser_offset.vector().isApprox(params.laser_offset.vector()));
  const Pose2 laser = robot.Compose(params.laser_offset);
  int no_returns = 0;
  for (int i = 0; i < 180; ++i) {
    const double a = laser.theta() - kPi / 2 + i * kPi / 180;
    const double r = CastRay(maze, laser.translation(), {std::cos(a), std::sin(a)}, 1e3);
    if (r >= 15.0) {
      ++no_returns;
      EXPECT_FALSE(scan.IsReturn(i)) << i;
      EXPECT_EQ(scan.ranges_m[i], static_cast<float>(params.max_range_m)) << i;
    } else {
      EXPECT_NEAR(scan.ranges_m[i], r, 1e-5) << i;
    }
  }
  EXPECT_GT(no_returns, 0);
  EXPECT_LT(no_returns, 180);
}

TEST(SimulateScan, MatchesTheIndependentRoomScan) {
  const FloorPlan room{testing::RoomWalls()};
  const Pose2 pose(1.0, -1.0, 0.4);
  Rng rng(1);
  const LaserScan scan = SimulateScan(room, pose, NoiseFree(), rng);
  const LaserScan reference = testing::RoomScan(pose);
  ASSERT_EQ(scan.ranges_m.size(), reference.ranges_m.size());
  EXPECT_DOUBLE_EQ(scan.angle_min_rad, reference.angle_min_rad);
  EXPECT_DOUBLE_EQ(scan.angle_increment_rad, reference.angle_increment_rad);
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    EXPECT_NEAR(scan.ranges_m[i], reference.ranges_m[i], 1e-5) << i;
  }
}

// In the maze's left corridor at (1.1, 12.5) facing +x: 12.5 m to the walls below and above,
// 23.9 m ahead along the corridor centre line.
TEST(SimulateScan, AngleConventionFor180And181Beams) {
  const FloorPlan maze = MakeSquareMaze();
  const Pose2 pose(1.1, 12.5, 0.0);
  Rng rng(1);
  LaserSimParams params = NoiseFree();
  const LaserScan even = SimulateScan(maze, pose, params, rng);
  ASSERT_EQ(even.ranges_m.size(), 180u);
  EXPECT_DOUBLE_EQ(even.angle_min_rad, -kPi / 2);
  EXPECT_DOUBLE_EQ(even.angle_increment_rad, kPi / 180);
  EXPECT_NEAR(even.BeamAngle(179), kPi / 2 - kPi / 180, 1e-12);
  EXPECT_NEAR(even.ranges_m[0], 12.5, 1e-5);
  EXPECT_NEAR(even.ranges_m[90], 23.9, 1e-5);

  params.beams = 181;
  const LaserScan odd = SimulateScan(maze, pose, params, rng);
  ASSERT_EQ(odd.ranges_m.size(), 181u);
  EXPECT_DOUBLE_EQ(odd.angle_min_rad, -kPi / 2);
  EXPECT_DOUBLE_EQ(odd.angle_increment_rad, kPi / 180);
  EXPECT_NEAR(odd.BeamAngle(180), kPi / 2, 1e-12);
  EXPECT_NEAR(odd.ranges_m[0], 12.5, 1e-5);
  EXPECT_NEAR(odd.ranges_m[90], 23.9, 1e-5);
  EXPECT_NEAR(odd.ranges_m[180], 12.5, 1e-5);

  params.beams = 1;
  const LaserScan single = SimulateScan(maze, pose, params, rng);
  ASSERT_EQ(single.ranges_m.size(), 1u);
  EXPECT_NEAR(single.ranges_m[0], 23.9, 1e-5);
  params.beams = 0;
  EXPECT_THROW(SimulateScan(maze, pose, params, rng), std::invalid_argument);
}

TEST(SimulateScan, LaserOffsetMovesTheSensor) {
  const FloorPlan maze = MakeSquareMaze();
  const Pose2 robot(12.5, 6.8, -2.0);
  LaserSimParams mounted = NoiseFree();
  mounted.laser_offset = Pose2(0.3, -0.1, kPi / 2);
  Rng rng(1);
  const LaserScan scan = SimulateScan(maze, robot, mounted, rng);
  const Pose2 laser = robot.Compose(mounted.laser_offset);
  const LaserScan direct = SimulateScan(maze, laser, NoiseFree(), rng);
  EXPECT_EQ(scan.ranges_m, direct.ranges_m);
}

TEST(SimulateScan, NoiseOnReturnsHasTheGivenSigma) {
  const FloorPlan maze = MakeSquareMaze();
  const Pose2 pose(6.8, 12.5, 0.3);
  LaserSimParams params = NoiseFree();
  params.range_limit_m = 5.0;
  Rng rng(2);
  const LaserScan truth = SimulateScan(maze, pose, params, rng);
  params.sigma_range_m = 0.05;
  double sum = 0.0, sum_sq = 0.0;
  int n = 0;
  for (int k = 0; k < 200; ++k) {
    const LaserScan scan = SimulateScan(maze, pose, params, rng);
    for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
      if (!truth.IsReturn(static_cast<int>(i))) {
        ASSERT_EQ(scan.ranges_m[i], truth.ranges_m[i]) << "no-returns stay noise-free";
        continue;
      }
      const double e = scan.ranges_m[i] - truth.ranges_m[i];
      sum += e;
      sum_sq += e * e;
      ++n;
    }
  }
  ASSERT_GT(n, 10000);
  const double mean = sum / n;
  EXPECT_NEAR(mean, 0.0, 0.002);
  EXPECT_NEAR(std::sqrt(sum_sq / n - mean * mean), 0.05, 0.05 * 0.03);
}

// Once around the maze's outer ring corridor, counter-clockwise.
GridSimParams RingRun() {
  GridSimParams params;
  params.route.waypoints_m = {{1.1, 1.1}, {23.9, 1.1}, {23.9, 23.9}, {1.1, 23.9}};
  params.route.loops = 1;
  return params;
}

TEST(SimulateGridRun, NoiseFreeOdometryIsTheTruth) {
  const FloorPlan maze = MakeSquareMaze();
  GridSimParams params = RingRun();
  params.sigma_v_mps = 0.0;
  params.sigma_omega_radps = 0.0;
  params.laser.sigma_range_m = 0.0;
  const Pose2 start(1.1, 1.1, 0.0);
  Rng rng(4);
  const GridSimRun run = SimulateGridRun(maze, params, start, rng);
  // 4 × 22.8 m at 0.5 m/s is 182 s, a little less with corners cut.
  ASSERT_GT(run.scans.size(), 1600u);
  ASSERT_LT(run.scans.size(), 1900u);
  ASSERT_EQ(run.truth.size(), run.scans.size());
  EXPECT_TRUE(run.truth[0].pose.vector().isApprox(start.vector()));
  Rng scan_rng(9);
  for (std::size_t k = 0; k < run.scans.size(); ++k) {
    const LaserScan& scan = run.scans[k];
    EXPECT_DOUBLE_EQ(scan.t_s, k * params.dt_s);
    EXPECT_DOUBLE_EQ(run.truth[k].t_s, scan.t_s);
    EXPECT_LT((scan.odometry.vector() - run.truth[k].pose.vector()).norm(), 1e-12);
    EXPECT_EQ(scan.logged_pose.vector(), scan.odometry.vector());
    const auto nearest = *std::min_element(scan.ranges_m.begin(), scan.ranges_m.end());
    EXPECT_GT(nearest, 0.4f) << "scan " << k << " too close to a wall";
    if (k % 100 == 0) {
      const LaserScan expected = SimulateScan(maze, run.truth[k].pose, params.laser, scan_rng);
      EXPECT_EQ(scan.ranges_m, expected.ranges_m) << "scan " << k;
    }
  }
}

TEST(SimulateGridRun, DeterministicPerSeed) {
  const FloorPlan maze = MakeSquareMaze();
  GridSimParams params = RingRun();
  params.max_steps = 300;
  const Pose2 start(1.1, 1.1, 0.0);
  Rng a(7), b(7), c(8);
  const GridSimRun run_a = SimulateGridRun(maze, params, start, a);
  const GridSimRun run_b = SimulateGridRun(maze, params, start, b);
  const GridSimRun run_c = SimulateGridRun(maze, params, start, c);
  ASSERT_EQ(run_a.scans.size(), 301u);
  ASSERT_EQ(run_b.scans.size(), run_a.scans.size());
  bool differs = false;
  for (std::size_t k = 0; k < run_a.scans.size(); ++k) {
    EXPECT_EQ(run_a.scans[k].ranges_m, run_b.scans[k].ranges_m);
    EXPECT_EQ(run_a.scans[k].odometry.vector(), run_b.scans[k].odometry.vector());
    differs = differs || run_a.scans[k].odometry.vector() != run_c.scans[k].odometry.vector();
  }
  EXPECT_TRUE(differs);
}

// The scans are the filter's inputs: they carry the noisy odometry, in `odometry` and in
// `logged_pose` as a raw log does, and the truth is only in run.truth.
TEST(SimulateGridRun, ScansCarryOdometryNotTheTruth) {
  const FloorPlan maze = MakeSquareMaze();
  GridSimParams params = RingRun();
  params.max_steps = 600;
  params.laser.beams = 2;  // the ranges do not matter here
  Rng rng(12);
  const GridSimRun run = SimulateGridRun(maze, params, Pose2(1.1, 1.1, 0.0), rng);
  ASSERT_EQ(run.scans.size(), run.truth.size());
  int away_from_truth = 0;
  for (std::size_t k = 0; k < run.scans.size(); ++k) {
    const LaserScan& scan = run.scans[k];
    EXPECT_EQ(scan.logged_pose.vector(), scan.odometry.vector()) << "scan " << k;
    const double off_m =
        (scan.logged_pose.translation() - run.truth[k].pose.translation()).norm();
    away_from_truth += off_m > 1e-3 ? 1 : 0;
  }
  // Odometry drifts from the first step on: nearly every logged pose is away from the truth.
  EXPECT_GT(away_from_truth, static_cast<int>(0.9 * run.scans.size()));
}

// Mean over seeds of the odometry position error at the quarter and at the end of the ring run.
std::pair<double, double> MeanDrift(double noise_scale) {
  const FloorPlan maze = MakeSquareMaze();
  GridSimParams params = RingRun();
  params.sigma_v_mps = 0.02 * noise_scale;
  params.sigma_omega_radps = 0.005 * noise_scale;
  params.laser.beams = 2;  // the scans do not matter here
  double quarter = 0.0, end = 0.0;
  constexpr int kSeeds = 8;
  for (int seed = 0; seed < kSeeds; ++seed) {
    Rng rng(100 + seed);
    const GridSimRun run = SimulateGridRun(maze, params, Pose2(1.1, 1.1, 0.0), rng);
    auto error = [&](std::size_t k) {
      return (run.scans[k].odometry.translation() - run.truth[k].pose.translation()).norm();
    };
    quarter += error(run.scans.size() / 4) / kSeeds;
    end += error(run.scans.size() - 1) / kSeeds;
  }
  return {quarter, end};
}

TEST(SimulateGridRun, OdometryDriftGrowsWithNoiseAndTime) {
  const auto [quarter_0, end_0] = MeanDrift(0.0);
  const auto [quarter_1, end_1] = MeanDrift(1.0);
  const auto [quarter_4, end_4] = MeanDrift(4.0);
  EXPECT_EQ(end_0, 0.0);
  EXPECT_GT(end_1, 0.05);
  EXPECT_GT(end_4, 2.0 * end_1);
  EXPECT_GT(end_1, quarter_1);
  EXPECT_GT(end_4, quarter_4);
  EXPECT_EQ(quarter_0, 0.0);
}

}  // namespace
}  // namespace slamkit
