#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

#include "slamkit/core/angle.hpp"
#include "slamkit/models/unicycle.hpp"
#include "slamkit/sim/scenario.hpp"

namespace slamkit {
namespace {

// The landmarks in id order, so that the noise draws do not depend on the world's order.
std::vector<const Landmark*> SortedById(const LandmarkWorld& world) {
  std::vector<const Landmark*> sorted;
  sorted.reserve(world.landmarks.size());
  for (const Landmark& l : world.landmarks) sorted.push_back(&l);
  std::sort(sorted.begin(), sorted.end(),
            [](const Landmark* a, const Landmark* b) { return a->id < b->id; });
  return sorted;
}

// One scan: the observations (without ids) and, parallel to them, their true landmark ids.
struct Scan {
  std::vector<PointObservation> observations;
  std::vector<LandmarkId> ids;
};

// Every landmark the sensor sees from the true pose, with (range, bearing) noise drawn from
// `noise_rng` in id order, range before bearing; then the scan is put in a random order drawn from
// `order_rng` (Fisher-Yates with our own index draw, so the order does not depend on the standard
// library), so that the filter cannot learn anything from the order either.
Scan Observe(const RangeBearingModel& sensor, const Pose2& pose,
             const std::vector<const Landmark*>& landmarks, Rng& noise_rng, Rng& order_rng) {
  const Eigen::Matrix2d R = sensor.NoiseCovariance();
  const double sigma_range_m = std::sqrt(R(0, 0));
  const double sigma_bearing_rad = std::sqrt(R(1, 1));
  Scan scan;
  for (const Landmark* landmark : landmarks) {
    if (!sensor.IsVisible(pose, landmark->position_m)) continue;
    const Eigen::Vector2d z = sensor.Predict(pose, landmark->position_m);
    PointObservation obs;
    obs.z.x() = z.x() + noise_rng.Normal(0.0, sigma_range_m);
    obs.z.y() = WrapAngle(z.y() + noise_rng.Normal(0.0, sigma_bearing_rad));
    obs.R = R;  // obs.id stays kNoLandmark: the truth goes beside
    scan.observations.push_back(obs);
    scan.ids.push_back(landmark->id);
  }
  for (std::size_t i = scan.ids.size(); i > 1; --i) {
    const auto j = std::min(static_cast<std::size_t>(order_rng.Uniform() * double(i)), i - 1);
    std::swap(scan.observations[i - 1], scan.observations[j]);
    std::swap(scan.ids[i - 1], scan.ids[j]);
  }
  return scan;
}

// Moves the true vehicle noise-free with `command` and returns the noisy control the filter gets.
// Unicycle and car-like: command + N(0, Q). Odometry: the robot drives as a unicycle and reports
// its true increment (dx, dy, dθ) in its own frame + N(0, Q).
Control MoveTruth(const MotionModel& model, MotionKind kind, const Control& command, double dt_s,
                  Pose2* pose, Rng& rng) {
  Control control;
  if (kind == MotionKind::kOdometry) {
    const Pose2 next = UnicycleModel().Move(*pose, command, dt_s);
    control = pose->Between(next).vector();
    *pose = next;
  } else {
    control = command;
    *pose = model.Move(*pose, command, dt_s);
  }
  const Eigen::MatrixXd Q = model.Noise(control, dt_s);
  control += rng.MultivariateNormal(Q);
  return control;
}

}  // namespace

void CopyTrueIds(const SimTruth& truth, SimInputs& inputs) {
  auto copy = [](const std::vector<LandmarkId>& ids, std::vector<PointObservation>& observations) {
    if (ids.size() != observations.size()) {
      throw std::invalid_argument("CopyTrueIds: truth and inputs differ in length");
    }
    for (std::size_t i = 0; i < ids.size(); ++i) observations[i].id = ids[i];
  };
  if (truth.ids.size() != inputs.steps.size()) {
    throw std::invalid_argument("CopyTrueIds: truth and inputs differ in length");
  }
  copy(truth.initial_ids, inputs.initial_observations);
  for (std::size_t k = 0; k < inputs.steps.size(); ++k) {
    copy(truth.ids[k], inputs.steps[k].observations);
  }
}

SimRun Simulate(const ScenarioParams& scenario, const LandmarkWorld& world, Rng& noise_rng,
                Rng& order_rng) {
  const std::unique_ptr<MotionModel> model = MakeMotionModel(scenario.vehicle);
  const RangeBearingModel sensor(scenario.sensor);
  const std::vector<const Landmark*> landmarks = SortedById(world);
  const int period = std::max(1, scenario.sensor_period_steps);
  WaypointController controller(scenario.route, scenario.controller, scenario.vehicle.kind);

  SimRun run;
  SimInputs& in = run.inputs;
  SimTruth& truth = run.truth;
  in.initial_pose = scenario.initial_pose;
  Pose2 pose = scenario.initial_pose;
  truth.poses.push_back({0.0, pose});
  Scan initial = Observe(sensor, pose, landmarks, noise_rng, order_rng);
  in.initial_observations = std::move(initial.observations);
  truth.initial_ids = std::move(initial.ids);
  for (int k = 0; k < scenario.max_steps; ++k) {
    const Control command = controller.Command(pose, scenario.dt_s);
    if (controller.Done()) break;
    SimStep step;
    step.t_s = (k + 1) * scenario.dt_s;
    step.control =
        MoveTruth(*model, scenario.vehicle.kind, command, scenario.dt_s, &pose, noise_rng);
    std::vector<LandmarkId> ids;
    if ((k + 1) % period == 0) {
      Scan scan = Observe(sensor, pose, landmarks, noise_rng, order_rng);
      step.observations = std::move(scan.observations);
      ids = std::move(scan.ids);
    }
    truth.poses.push_back({step.t_s, pose});
    truth.ids.push_back(std::move(ids));
    in.steps.push_back(std::move(step));
  }
  return run;
}

}  // namespace slamkit
