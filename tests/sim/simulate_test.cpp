#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "slamkit/core/angle.hpp"
#include "slamkit/models/unicycle.hpp"
#include "slamkit/sim/scenario.hpp"

namespace slamkit {
namespace {

ScenarioParams SmallScenario() {
  ScenarioParams s;
  s.dt_s = 0.05;
  s.max_steps = 20000;
  s.world.uniform = {{-10.0, -10.0}, {40.0, 40.0}, 80, 0.0};
  s.world.seed = 5;
  s.route.waypoints_m = {{0.0, 0.0}, {30.0, 0.0}, {30.0, 30.0}, {0.0, 30.0}};
  s.route.switch_distance_m = 2.0;
  s.sensor.max_range_m = 15.0;
  s.sensor.min_range_m = 1.0;
  s.sensor.fov_rad = DegToRad(90.0);
  s.sensor_period_steps = 4;
  return s;
}

struct Residuals {
  std::vector<double> values;
  void Add(double v) { values.push_back(v); }
  double Mean() const {
    double sum = 0.0;
    for (double v : values) sum += v;
    return sum / values.size();
  }
  double Std() const {
    const double mean = Mean();
    double sum = 0.0;
    for (double v : values) sum += (v - mean) * (v - mean);
    return std::sqrt(sum / (values.size() - 1));
  }
  // Mean within 4 standard errors of zero, standard deviation within 5 % of `sigma`.
  void ExpectGaussian(double sigma) const {
    ASSERT_GT(values.size(), 2000u);
    EXPECT_LT(std::abs(Mean()), 4.0 * sigma / std::sqrt(values.size()));
    EXPECT_NEAR(Std(), sigma, 0.05 * sigma);
  }
};

bool SameRun(const SimRun& a, const SimRun& b) {
  if (a.steps.size() != b.steps.size()) return false;
  for (std::size_t k = 0; k < a.steps.size(); ++k) {
    const SimStep &x = a.steps[k], &y = b.steps[k];
    if (x.t_s != y.t_s || x.true_pose.vector() != y.true_pose.vector()) return false;
    if (x.control != y.control || x.observations.size() != y.observations.size()) return false;
    for (std::size_t i = 0; i < x.observations.size(); ++i) {
      if (x.observations[i].z != y.observations[i].z) return false;
      if (x.observations[i].id != y.observations[i].id) return false;
    }
  }
  return true;
}

TEST(Simulate, SameSeedSameRunOtherSeedOtherNoise) {
  const ScenarioParams s = SmallScenario();
  const LandmarkWorld world = MakeWorld(s.world);
  Rng a(1), b(1), c(2);
  const SimRun run_a = Simulate(s, world, a);
  EXPECT_TRUE(SameRun(run_a, Simulate(s, world, b)));
  const SimRun run_c = Simulate(s, world, c);
  EXPECT_FALSE(SameRun(run_a, run_c));
  // The noise changes with the seed; the true trajectory does not.
  ASSERT_EQ(run_a.steps.size(), run_c.steps.size());
  EXPECT_EQ(run_a.steps.back().true_pose.vector(), run_c.steps.back().true_pose.vector());
  EXPECT_NE(run_a.steps.back().control, run_c.steps.back().control);
}

TEST(Simulate, StepsTimesAndRouteEnd) {
  const ScenarioParams s = SmallScenario();
  Rng rng(3);
  const SimRun run = Simulate(s, MakeWorld(s.world), rng);
  EXPECT_EQ(run.initial_pose.vector(), s.initial_pose.vector());
  ASSERT_GT(run.steps.size(), 100u);
  EXPECT_LT(run.steps.size(), static_cast<std::size_t>(s.max_steps));  // the route ended it
  EXPECT_LE((run.steps.back().true_pose.translation() - s.route.waypoints_m[0]).norm(), 2.1);
  for (std::size_t k = 0; k < run.steps.size(); ++k) {
    EXPECT_DOUBLE_EQ(run.steps[k].t_s, (k + 1) * s.dt_s);
    if ((k + 1) % 4 != 0) {
      EXPECT_TRUE(run.steps[k].observations.empty()) << k;
    }
  }
  ScenarioParams capped = s;
  capped.max_steps = 37;
  EXPECT_EQ(Simulate(capped, MakeWorld(s.world), rng).steps.size(), 37u);
}

TEST(Simulate, ObservesExactlyTheVisibleLandmarksInIdOrder) {
  ScenarioParams s = SmallScenario();
  LandmarkWorld world = MakeWorld(s.world);
  std::reverse(world.landmarks.begin(), world.landmarks.end());  // ids out of order
  const RangeBearingModel sensor(s.sensor);
  Rng rng(4);
  const SimRun run = Simulate(s, world, rng);
  int seen = 0, hidden = 0;
  for (std::size_t k = 3; k < run.steps.size(); k += 4) {
    const SimStep& step = run.steps[k];
    std::vector<LandmarkId> expected;
    for (auto it = world.landmarks.rbegin(); it != world.landmarks.rend(); ++it) {
      if (sensor.IsVisible(step.true_pose, it->position_m)) expected.push_back(it->id);
    }
    std::vector<LandmarkId> ids;
    for (const PointObservation& obs : step.observations) {
      ids.push_back(obs.id);
      EXPECT_EQ(obs.R, sensor.NoiseCovariance());
      EXPECT_LE(std::abs(obs.z.y()), 0.5 * s.sensor.fov_rad + 0.1);
      EXPECT_LE(obs.z.x(), s.sensor.max_range_m + 0.5);
    }
    EXPECT_EQ(ids, expected) << "step " << k;
    seen += static_cast<int>(ids.size());
    hidden += static_cast<int>(world.landmarks.size() - ids.size());
  }
  EXPECT_GT(seen, 500);  // the test is not vacuous: landmarks are seen and others hidden
  EXPECT_GT(hidden, 500);
}

TEST(Simulate, MeasurementNoiseHasTheSensorStatistics) {
  ScenarioParams s = SmallScenario();
  s.sensor_period_steps = 1;
  s.sensor.sigma_range_m = 0.2;
  s.sensor.sigma_bearing_rad = DegToRad(2.0);
  s.sensor.fov_rad = 2.0 * std::numbers::pi;  // bearings near ±π: the noisy bearing must be wrapped
  const LandmarkWorld world = MakeWorld(s.world);
  Rng rng(8);
  const SimRun run = Simulate(s, world, rng);
  Residuals range, bearing;
  for (const SimStep& step : run.steps) {
    for (const PointObservation& obs : step.observations) {
      const RangeBearing z =
          PredictRangeBearing(step.true_pose, world.landmarks[obs.id].position_m);
      range.Add(obs.z.x() - z.range_m);
      bearing.Add(WrapAngle(obs.z.y() - z.bearing_rad));
      EXPECT_GE(obs.z.y(), -std::numbers::pi);
      EXPECT_LT(obs.z.y(), std::numbers::pi);
    }
  }
  range.ExpectGaussian(0.2);
  bearing.ExpectGaussian(DegToRad(2.0));
}

TEST(Simulate, CarLikeControlIsCommandPlusNoise) {
  ScenarioParams s = SmallScenario();
  s.vehicle.car_like.sigma_v_mps = 0.3;
  s.route.loops = 4;
  Rng rng(9);
  const SimRun run = Simulate(s, MakeWorld(s.world), rng);
  Residuals speed;
  for (const SimStep& step : run.steps) speed.Add(step.control[0] - s.controller.speed_mps);
  speed.ExpectGaussian(0.3);
  // The truth moved noise-free with the commanded speed.
  const double step_m = s.controller.speed_mps * s.dt_s;
  EXPECT_NEAR((run.steps[1].true_pose.translation() - run.steps[0].true_pose.translation()).norm(),
              step_m, 1e-9);
}

TEST(Simulate, OdometryControlIsTrueIncrementPlusNoise) {
  ScenarioParams s = SmallScenario();
  s.vehicle.kind = MotionKind::kOdometry;
  s.vehicle.odometry = {0.04, DegToRad(0.5)};
  s.controller.speed_mps = 1.0;
  Rng rng(10);
  const SimRun run = Simulate(s, MakeWorld(s.world), rng);
  Residuals dx, dy, dtheta;
  Pose2 previous = run.initial_pose;
  for (const SimStep& step : run.steps) {
    const Eigen::Vector3d truth = previous.Between(step.true_pose).vector();
    dx.Add(step.control[0] - truth.x());
    dy.Add(step.control[1] - truth.y());
    dtheta.Add(WrapAngle(step.control[2] - truth.z()));
    // The robot drives as a unicycle: no sideways motion.
    EXPECT_NEAR(std::abs(std::atan2(truth.y(), truth.x())), std::abs(0.5 * truth.z()), 1e-9);
    previous = step.true_pose;
  }
  dx.ExpectGaussian(0.04);
  dy.ExpectGaussian(0.04);
  dtheta.ExpectGaussian(DegToRad(0.5));
}

}  // namespace
}  // namespace slamkit
