#include <algorithm>
#include <cmath>
#include <memory>

#include "slamkit/core/angle.hpp"
#include "slamkit/models/unicycle.hpp"
#include "slamkit/sim/scenario.hpp"

namespace slamkit {
namespace {

// The landmarks in id order, so observations come out sorted by id whatever the world's order.
std::vector<const Landmark*> SortedById(const LandmarkWorld& world) {
  std::vector<const Landmark*> sorted;
  sorted.reserve(world.landmarks.size());
  for (const Landmark& l : world.landmarks) sorted.push_back(&l);
  std::sort(sorted.begin(), sorted.end(),
            [](const Landmark* a, const Landmark* b) { return a->id < b->id; });
  return sorted;
}

// Every landmark the sensor sees from the true pose, with (range, bearing) noise drawn in id
// order, range before bearing.
std::vector<PointObservation> Observe(const RangeBearingModel& sensor, const Pose2& pose,
                                      const std::vector<const Landmark*>& landmarks, Rng& rng) {
  const Eigen::Matrix2d R = sensor.NoiseCovariance();
  const double sigma_range_m = std::sqrt(R(0, 0));
  const double sigma_bearing_rad = std::sqrt(R(1, 1));
  std::vector<PointObservation> observations;
  for (const Landmark* landmark : landmarks) {
    if (!sensor.IsVisible(pose, landmark->position_m)) continue;
    const Eigen::Vector2d z = sensor.Predict(pose, landmark->position_m);
    PointObservation obs;
    obs.z.x() = z.x() + rng.Normal(0.0, sigma_range_m);
    obs.z.y() = WrapAngle(z.y() + rng.Normal(0.0, sigma_bearing_rad));
    obs.R = R;
    obs.id = landmark->id;
    observations.push_back(obs);
  }
  return observations;
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

SimRun Simulate(const ScenarioParams& scenario, const LandmarkWorld& world, Rng& rng) {
  const std::unique_ptr<MotionModel> model = MakeMotionModel(scenario.vehicle);
  const RangeBearingModel sensor(scenario.sensor);
  const std::vector<const Landmark*> landmarks = SortedById(world);
  const int period = std::max(1, scenario.sensor_period_steps);
  WaypointController controller(scenario.route, scenario.controller, scenario.vehicle.kind);

  SimRun run;
  run.initial_pose = scenario.initial_pose;
  Pose2 pose = scenario.initial_pose;
  run.initial_observations = Observe(sensor, pose, landmarks, rng);
  for (int k = 0; k < scenario.max_steps; ++k) {
    const Control command = controller.Command(pose, scenario.dt_s);
    if (controller.Done()) break;
    SimStep step;
    step.t_s = (k + 1) * scenario.dt_s;
    step.control = MoveTruth(*model, scenario.vehicle.kind, command, scenario.dt_s, &pose, rng);
    step.true_pose = pose;
    if ((k + 1) % period == 0) step.observations = Observe(sensor, pose, landmarks, rng);
    run.steps.push_back(std::move(step));
  }
  return run;
}

}  // namespace slamkit
