// The shipped configs do what their comments and docs/scenario.md promise.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "slamkit/core/angle.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

ScenarioConfig Load(const char* name) {
  return LoadScenario(fs::path(SLAMKIT_SOURCE_DIR) / "configs" / name);
}

int SensorSteps(const SimRun& run) {
  const std::vector<SimStep>& steps = run.inputs.steps;
  return static_cast<int>(std::count_if(steps.begin(), steps.end(),
                                        [](const SimStep& s) { return !s.observations.empty(); }));
}

// The closest the true trajectory came to each waypoint.
std::vector<double> ClosestApproach(const SimRun& run, const RouteParams& route) {
  std::vector<double> closest(route.waypoints_m.size(), 1e9);
  for (const StampedPose& truth : run.truth.poses) {
    for (std::size_t w = 0; w < closest.size(); ++w) {
      closest[w] =
          std::min(closest[w], (route.waypoints_m[w] - truth.pose.translation()).norm());
    }
  }
  return closest;
}

double MinSpacing(const LandmarkWorld& world) {
  double spacing = 1e9;
  for (std::size_t i = 0; i < world.landmarks.size(); ++i) {
    for (std::size_t j = i + 1; j < world.landmarks.size(); ++j) {
      spacing =
          std::min(spacing, (world.landmarks[i].position_m - world.landmarks[j].position_m).norm());
    }
  }
  return spacing;
}

TEST(ShippedConfigs, DefaultDrivesOneFullLoopUnder5000Steps) {
  const ScenarioConfig c = Load("default.yaml");
  const ScenarioParams& s = c.scenario;
  EXPECT_EQ(s.vehicle.kind, MotionKind::kCarLike);
  EXPECT_EQ(s.vehicle.car_like.wheelbase_m, 4.0);
  EXPECT_EQ(s.dt_s, 0.025);
  EXPECT_EQ(s.sensor_period_steps, 8);
  EXPECT_DOUBLE_EQ(s.sensor.fov_rad, DegToRad(180.0));
  EXPECT_DOUBLE_EQ(s.sensor.sigma_bearing_rad, DegToRad(1.0));
  EXPECT_FALSE(c.ekf.known_association());
  EXPECT_EQ(c.ekf.jacobians, JacobianEstimates::kFirstEstimates);
  const LandmarkWorld world = MakeWorld(s.world);
  EXPECT_GE(world.landmarks.size(), 60u);
  EXPECT_LE(world.landmarks.size(), 100u);
  Rng rng(1), order(1);
  const SimRun run = Simulate(s, world, rng, order);
  EXPECT_LT(run.inputs.steps.size(), 5000u);
  for (double d : ClosestApproach(run, s.route)) EXPECT_LE(d, s.route.switch_distance_m);
  EXPECT_LE((run.truth.poses.back().pose.translation() - s.route.waypoints_m[0]).norm(),
            s.route.switch_distance_m);
  EXPECT_GT(SensorSteps(run), 400);
}

TEST(ShippedConfigs, Square400RunsExactly1000StepsOverAtLeastOneLap) {
  const ScenarioConfig c = Load("square_400.yaml");
  const ScenarioParams& s = c.scenario;
  EXPECT_EQ(s.vehicle.kind, MotionKind::kOdometry);
  EXPECT_TRUE(c.ekf.known_association());
  const LandmarkWorld world = MakeWorld(s.world);
  ASSERT_EQ(world.landmarks.size(), 400u);
  for (const Landmark& l : world.landmarks) {
    EXPECT_TRUE((l.position_m.array() >= -5.0).all() && (l.position_m.array() <= 25.0).all());
  }
  Rng rng(1), order(1);
  const SimRun run = Simulate(s, world, rng, order);
  EXPECT_EQ(run.inputs.steps.size(), 1000u);
  EXPECT_EQ(SensorSteps(run), 1000);
  // One lap: every corner reached, and back at the start after the last one.
  const std::vector<double> closest = ClosestApproach(run, s.route);
  for (double d : closest) EXPECT_LE(d, s.route.switch_distance_m);
  const Trajectory& truth = run.truth.poses;  // truth[k + 1] is after step k
  const auto back_home =
      std::find_if(truth.begin() + 701, truth.end(), [&](const StampedPose& p) {
        return p.pose.translation().norm() <= s.route.switch_distance_m;
      });
  EXPECT_NE(back_home, truth.end());
}

TEST(ShippedConfigs, ShortIsShortWithSparseLandmarks) {
  const ScenarioConfig c = Load("short.yaml");
  const ScenarioParams& s = c.scenario;
  EXPECT_TRUE(c.ekf.known_association());
  const LandmarkWorld world = MakeWorld(s.world);
  EXPECT_EQ(world.landmarks.size(), 30u);
  EXPECT_GT(MinSpacing(world), 5.0);
  Rng rng(1), order(1);
  const SimRun run = Simulate(s, world, rng, order);
  EXPECT_LT(run.inputs.steps.size(), 1500u);
  EXPECT_GE(SensorSteps(run), 130);
  EXPECT_LE(SensorSteps(run), 170);
  for (double d : ClosestApproach(run, s.route)) EXPECT_LE(d, s.route.switch_distance_m);
  // The route keeps clear of the landmarks (no near-zero ranges).
  for (const StampedPose& truth : run.truth.poses) {
    for (const Landmark& l : world.landmarks) {
      EXPECT_GT((l.position_m - truth.pose.translation()).norm(), 4.0);
    }
  }
}

// Seed 001 Sec. 4: a 100 m × 100 m world with three dense clusters, a 14-waypoint route, the
// car-like vehicle of Eq. 2, and SWSLAM's trigger on 3 observation periods.
TEST(ShippedConfigs, SwslamIsTheSeedsWorldAndRoute) {
  const ScenarioConfig c = Load("swslam.yaml");
  const ScenarioParams& s = c.scenario;
  EXPECT_EQ(s.vehicle.kind, MotionKind::kCarLike);
  EXPECT_EQ(c.planner.kind, PlannerKind::kSwslam);
  EXPECT_EQ(c.planner.swslam.trigger_periods, 3);
  EXPECT_FALSE(c.ekf.known_association());
  ASSERT_EQ(s.route.waypoints_m.size(), 14u);
  for (const Eigen::Vector2d& w : s.route.waypoints_m) {
    EXPECT_TRUE((w.array() >= 0.0).all() && (w.array() <= 100.0).all());
  }
  ASSERT_EQ(s.world.clusters.size(), 4u);  // three dense, one sparse background
  for (int i = 0; i < 3; ++i) EXPECT_LE(s.world.clusters[i].sigma_m, 5.0);
  EXPECT_GE(s.world.clusters[3].sigma_m, 20.0);
  const LandmarkWorld world = MakeWorld(s.world);
  Rng rng(1), order(1);
  const SimRun run = Simulate(s, world, rng, order);  // the route alone
  EXPECT_LT(static_cast<int>(run.inputs.steps.size()), s.max_steps);
  for (double d : ClosestApproach(run, s.route)) EXPECT_LE(d, s.route.switch_distance_m);
  EXPECT_GT(SensorSteps(run), 400);
}

}  // namespace
}  // namespace slamkit
