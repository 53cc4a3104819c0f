#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
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
  if (a.inputs.steps.size() != b.inputs.steps.size()) return false;
  if (a.truth.ids != b.truth.ids || a.truth.initial_ids != b.truth.initial_ids) return false;
  for (std::size_t k = 0; k < a.inputs.steps.size(); ++k) {
    const SimStep &x = a.inputs.steps[k], &y = b.inputs.steps[k];
    if (x.t_s != y.t_s) return false;
    if (a.truth.poses[k + 1].pose.vector() != b.truth.poses[k + 1].pose.vector()) return false;
    if (x.control != y.control || x.observations.size() != y.observations.size()) return false;
    for (std::size_t i = 0; i < x.observations.size(); ++i) {
      if (x.observations[i].z != y.observations[i].z) return false;
    }
  }
  return true;
}

// Each scan's sightings as (true id, measurement), sorted by id: the scan without its order.
std::vector<std::vector<std::pair<LandmarkId, Eigen::Vector2d>>> SightingsById(const SimRun& run) {
  std::vector<std::vector<std::pair<LandmarkId, Eigen::Vector2d>>> scans;
  for (std::size_t k = 0; k < run.inputs.steps.size(); ++k) {
    std::vector<std::pair<LandmarkId, Eigen::Vector2d>> scan;
    for (std::size_t i = 0; i < run.inputs.steps[k].observations.size(); ++i) {
      scan.emplace_back(run.truth.ids[k][i], run.inputs.steps[k].observations[i].z);
    }
    std::sort(scan.begin(), scan.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    scans.push_back(std::move(scan));
  }
  return scans;
}

TEST(Simulate, SameSeedSameRunOtherSeedOtherNoise) {
  const ScenarioParams s = SmallScenario();
  const LandmarkWorld world = MakeWorld(s.world);
  Rng a(1), b(1), c(2), order_a(11), order_b(11), order_c(11);
  const SimRun run_a = Simulate(s, world, a, order_a);
  EXPECT_TRUE(SameRun(run_a, Simulate(s, world, b, order_b)));
  const SimRun run_c = Simulate(s, world, c, order_c);
  EXPECT_FALSE(SameRun(run_a, run_c));
  // The noise changes with the seed; the true trajectory does not.
  ASSERT_EQ(run_a.inputs.steps.size(), run_c.inputs.steps.size());
  EXPECT_EQ(run_a.truth.poses.back().pose.vector(), run_c.truth.poses.back().pose.vector());
  EXPECT_NE(run_a.inputs.steps.back().control, run_c.inputs.steps.back().control);
}

// The order has its own stream: another order seed shuffles the scans differently but draws
// exactly the same noise for each sighting.
TEST(Simulate, OrderStreamLeavesTheNoiseDrawsAlone) {
  const ScenarioParams s = SmallScenario();
  const LandmarkWorld world = MakeWorld(s.world);
  Rng a(1), b(1), order_a(21), order_b(22);
  const SimRun run_a = Simulate(s, world, a, order_a);
  const SimRun run_b = Simulate(s, world, b, order_b);
  EXPECT_NE(run_a.truth.ids, run_b.truth.ids);  // another order
  EXPECT_EQ(SightingsById(run_a), SightingsById(run_b));
  for (std::size_t k = 0; k < run_a.inputs.steps.size(); ++k) {
    ASSERT_EQ(run_a.inputs.steps[k].control, run_b.inputs.steps[k].control);
  }
}

TEST(Simulate, StepsTimesAndRouteEnd) {
  const ScenarioParams s = SmallScenario();
  Rng rng(3), order(3);
  const SimRun run = Simulate(s, MakeWorld(s.world), rng, order);
  const std::vector<SimStep>& steps = run.inputs.steps;
  EXPECT_EQ(run.inputs.initial_pose.vector(), s.initial_pose.vector());
  ASSERT_GT(steps.size(), 100u);
  EXPECT_LT(steps.size(), static_cast<std::size_t>(s.max_steps));  // the route ended it
  ASSERT_EQ(run.truth.poses.size(), steps.size() + 1);
  ASSERT_EQ(run.truth.ids.size(), steps.size());
  EXPECT_EQ(run.truth.poses[0].pose.vector(), s.initial_pose.vector());
  EXPECT_EQ(run.truth.poses[0].t_s, 0.0);
  EXPECT_LE((run.truth.poses.back().pose.translation() - s.route.waypoints_m[0]).norm(), 2.1);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    EXPECT_DOUBLE_EQ(steps[k].t_s, (k + 1) * s.dt_s);
    EXPECT_EQ(run.truth.poses[k + 1].t_s, steps[k].t_s);
    EXPECT_EQ(run.truth.ids[k].size(), steps[k].observations.size());
    if ((k + 1) % 4 != 0) {
      EXPECT_TRUE(steps[k].observations.empty()) << k;
    }
  }
  ScenarioParams capped = s;
  capped.max_steps = 37;
  EXPECT_EQ(Simulate(capped, MakeWorld(s.world), rng, order).inputs.steps.size(), 37u);
}

// The inputs are what a filter would receive with unknown association: no observation carries a
// landmark id, and the truth beside names exactly the visible landmarks, in an order that is not
// the id order.
TEST(Simulate, InputsCarryNoIdsAndTheTruthNamesTheVisibleLandmarksUnsorted) {
  ScenarioParams s = SmallScenario();
  LandmarkWorld world = MakeWorld(s.world);
  std::reverse(world.landmarks.begin(), world.landmarks.end());  // ids out of order
  const RangeBearingModel sensor(s.sensor);
  Rng rng(4), order(4);
  const SimRun run = Simulate(s, world, rng, order);
  int seen = 0, hidden = 0, scans_of_three = 0, unsorted = 0;
  for (const PointObservation& obs : run.inputs.initial_observations) {
    EXPECT_EQ(obs.id, kNoLandmark);
  }
  EXPECT_EQ(run.truth.initial_ids.size(), run.inputs.initial_observations.size());
  for (std::size_t k = 3; k < run.inputs.steps.size(); k += 4) {
    const SimStep& step = run.inputs.steps[k];
    const Pose2& pose = run.truth.poses[k + 1].pose;
    std::vector<LandmarkId> expected;
    for (const Landmark& l : world.landmarks) {
      if (sensor.IsVisible(pose, l.position_m)) expected.push_back(l.id);
    }
    std::sort(expected.begin(), expected.end());
    for (const PointObservation& obs : step.observations) {
      EXPECT_EQ(obs.id, kNoLandmark) << "step " << k;
      EXPECT_EQ(obs.R, sensor.NoiseCovariance());
      EXPECT_LE(std::abs(obs.z.y()), 0.5 * s.sensor.fov_rad + 0.1);
      EXPECT_LE(obs.z.x(), s.sensor.max_range_m + 0.5);
    }
    const std::vector<LandmarkId>& ids = run.truth.ids[k];
    ASSERT_EQ(ids.size(), step.observations.size());
    if (ids.size() >= 3) {
      ++scans_of_three;
      unsorted += std::is_sorted(ids.begin(), ids.end()) ? 0 : 1;
    }
    std::vector<LandmarkId> sorted = ids;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(sorted, expected) << "step " << k;
    seen += static_cast<int>(ids.size());
    hidden += static_cast<int>(world.landmarks.size() - ids.size());
  }
  EXPECT_GT(seen, 500);  // the test is not vacuous: landmarks are seen and others hidden
  EXPECT_GT(hidden, 500);
  // A random order of 3 or more is sorted with probability 1/6 at most.
  ASSERT_GT(scans_of_three, 50);
  EXPECT_GT(unsorted, 0.7 * scans_of_three) << unsorted << " of " << scans_of_three;
}

TEST(Simulate, CopyTrueIdsGivesKnownAssociationOnlyOnRequest) {
  const ScenarioParams s = SmallScenario();
  Rng rng(5), order(5);
  const SimRun run = Simulate(s, MakeWorld(s.world), rng, order);
  SimInputs known = run.inputs;
  CopyTrueIds(run.truth, known);
  int copied = 0;
  for (std::size_t k = 0; k < known.steps.size(); ++k) {
    for (std::size_t i = 0; i < known.steps[k].observations.size(); ++i) {
      EXPECT_EQ(known.steps[k].observations[i].id, run.truth.ids[k][i]);
      EXPECT_EQ(known.steps[k].observations[i].z, run.inputs.steps[k].observations[i].z);
      EXPECT_EQ(run.inputs.steps[k].observations[i].id, kNoLandmark);  // the original untouched
      ++copied;
    }
  }
  EXPECT_GT(copied, 500);
  SimTruth short_truth = run.truth;
  short_truth.ids.pop_back();
  EXPECT_THROW(CopyTrueIds(short_truth, known), std::invalid_argument);
}

TEST(Simulate, MeasurementNoiseHasTheSensorStatistics) {
  ScenarioParams s = SmallScenario();
  s.sensor_period_steps = 1;
  s.sensor.sigma_range_m = 0.2;
  s.sensor.sigma_bearing_rad = DegToRad(2.0);
  s.sensor.fov_rad = 2.0 * std::numbers::pi;  // bearings near ±π: the noisy bearing must be wrapped
  const LandmarkWorld world = MakeWorld(s.world);
  Rng rng(8), order(8);
  const SimRun run = Simulate(s, world, rng, order);
  Residuals range, bearing;
  for (std::size_t k = 0; k < run.inputs.steps.size(); ++k) {
    for (std::size_t i = 0; i < run.inputs.steps[k].observations.size(); ++i) {
      const PointObservation& obs = run.inputs.steps[k].observations[i];
      const RangeBearing z = PredictRangeBearing(
          run.truth.poses[k + 1].pose, world.landmarks[run.truth.ids[k][i]].position_m);
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
  Rng rng(9), order(9);
  const SimRun run = Simulate(s, MakeWorld(s.world), rng, order);
  Residuals speed;
  for (const SimStep& step : run.inputs.steps) {
    speed.Add(step.control[0] - s.controller.speed_mps);
  }
  speed.ExpectGaussian(0.3);
  // The truth moved noise-free with the commanded speed.
  const double step_m = s.controller.speed_mps * s.dt_s;
  const Trajectory& truth = run.truth.poses;
  EXPECT_NEAR((truth[2].pose.translation() - truth[1].pose.translation()).norm(), step_m, 1e-9);
}

TEST(Simulate, OdometryControlIsTrueIncrementPlusNoise) {
  ScenarioParams s = SmallScenario();
  s.vehicle.kind = MotionKind::kOdometry;
  s.vehicle.odometry = {0.04, DegToRad(0.5)};
  s.controller.speed_mps = 1.0;
  Rng rng(10), order(10);
  const SimRun run = Simulate(s, MakeWorld(s.world), rng, order);
  Residuals dx, dy, dtheta;
  Pose2 previous = run.inputs.initial_pose;
  for (std::size_t k = 0; k < run.inputs.steps.size(); ++k) {
    const SimStep& step = run.inputs.steps[k];
    const Pose2& pose = run.truth.poses[k + 1].pose;
    const Eigen::Vector3d truth = previous.Between(pose).vector();
    dx.Add(step.control[0] - truth.x());
    dy.Add(step.control[1] - truth.y());
    dtheta.Add(WrapAngle(step.control[2] - truth.z()));
    // The robot drives as a unicycle: no sideways motion.
    EXPECT_NEAR(std::abs(std::atan2(truth.y(), truth.x())), std::abs(0.5 * truth.z()), 1e-9);
    previous = pose;
  }
  dx.ExpectGaussian(0.04);
  dy.ExpectGaussian(0.04);
  dtheta.ExpectGaussian(DegToRad(0.5));
}

}  // namespace
}  // namespace slamkit
