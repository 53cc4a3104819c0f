#include "slamkit/sim/simulator.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "slamkit/core/angle.hpp"
#include "slamkit/models/unicycle.hpp"

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

Simulator::Simulator(const ScenarioParams& scenario, const LandmarkWorld& world, Rng& noise_rng,
                     Rng& order_rng)
    : dt_s_(scenario.dt_s),
      max_steps_(scenario.max_steps),
      period_steps_(std::max(1, scenario.sensor_period_steps)),
      kind_(scenario.vehicle.kind),
      model_(MakeMotionModel(scenario.vehicle)),
      sensor_(scenario.sensor),
      landmarks_(SortedById(world)),
      noise_rng_(noise_rng),
      order_rng_(order_rng),
      controller_(scenario.route, scenario.controller, scenario.vehicle.kind),
      pose_(scenario.initial_pose) {
  Scan initial = Observe(sensor_, pose_, landmarks_, noise_rng_, order_rng_);
  initial_obs_ = std::move(initial.observations);
  initial_ids_ = std::move(initial.ids);
}

Simulator::~Simulator() = default;

std::optional<SimStepWithTruth> Simulator::Step() {
  if (finished_ || k_ >= max_steps_) return std::nullopt;
  const Control command = controller_.Command(pose_, dt_s_);
  finished_ = controller_.Done();
  if (finished_) return std::nullopt;
  SimStepWithTruth out;
  out.inputs.t_s = (k_ + 1) * dt_s_;
  out.inputs.control = MoveTruth(*model_, kind_, command, dt_s_, &pose_, noise_rng_);
  out.sensor_period = (k_ + 1) % period_steps_ == 0;
  if (out.sensor_period) {
    Scan scan = Observe(sensor_, pose_, landmarks_, noise_rng_, order_rng_);
    out.inputs.observations = std::move(scan.observations);
    out.ids = std::move(scan.ids);
  }
  out.truth = {out.inputs.t_s, pose_};
  ++k_;
  return out;
}

}  // namespace slamkit
