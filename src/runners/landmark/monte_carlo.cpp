#include "slamkit/runners/landmark/monte_carlo.hpp"

#include <stdexcept>
#include <string>

#include "monte_carlo_batches.hpp"
#include "slamkit/core/numerical_error.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/runners/landmark/landmark_run.hpp"

namespace slamkit {

LandmarkFilterFactory EkfSlamFactory(const EkfSlamParams& ekf, const VehicleParams& vehicle,
                                     const RangeBearingParams& sensor) {
  return [ekf, vehicle, sensor]() -> std::unique_ptr<LandmarkSlamFilter> {
    return std::make_unique<EkfSlam>(ekf, MakeMotionModel(vehicle),
                                     std::make_unique<RangeBearingModel>(sensor));
  };
}

LandmarkFilterFactory EkfSlamFactory(const ScenarioConfig& config) {
  return EkfSlamFactory(config.ekf, config.scenario.vehicle, config.scenario.sensor);
}

LandmarkFilterFactory FastSlamFactory(const FastSlamParams& fastslam, const VehicleParams& vehicle,
                                      const RangeBearingParams& sensor) {
  return [fastslam, vehicle, sensor]() -> std::unique_ptr<LandmarkSlamFilter> {
    return std::make_unique<FastSlam>(fastslam, MakeMotionModel(vehicle),
                                      std::make_unique<RangeBearingModel>(sensor));
  };
}

RunResult RunLandmarkFilter(LandmarkSlamFilter& filter, const SimRun& sim,
                            const LandmarkWorld& world, double dt_s, bool known_association,
                            int map_snapshots) {
  const SimInputs& inputs = sim.inputs;
  const Trajectory& truth = sim.truth.poses;
  if (truth.size() != inputs.steps.size() + 1 || sim.truth.ids.size() != inputs.steps.size()) {
    throw std::invalid_argument("RunLandmarkFilter: truth and inputs differ in length");
  }
  LandmarkRunRecorder recorder(filter, known_association);
  recorder.KeepMapSnapshots(map_snapshots);
  recorder.Start(inputs.initial_pose, truth[0], inputs.initial_observations,
                 sim.truth.initial_ids);
  for (std::size_t k = 0; k < inputs.steps.size(); ++k) {
    recorder.Step(inputs.steps[k], dt_s, truth[k + 1], sim.truth.ids[k]);
  }
  return recorder.Finish(world);
}

namespace {

// Run k of a Monte Carlo set: its simulation, from its own streams of the seed, and its filter. A
// numerical failure names the run, so that it can be reproduced alone.
RunResult RunOne(const ScenarioParams& scenario, const LandmarkWorld& world,
                 const LandmarkFilterFactory& make_filter, const MonteCarloParams& params, int k) {
  const auto run = static_cast<std::uint64_t>(k);
  Rng noise_rng = Rng::ForStream(params.seed, run);
  Rng order_rng = Rng::ForStream(params.seed, internal::kObservationOrderStreams + run);
  const SimRun sim = Simulate(scenario, world, noise_rng, order_rng);
  const std::unique_ptr<LandmarkSlamFilter> filter = make_filter();
  try {
    return RunLandmarkFilter(*filter, sim, world, scenario.dt_s, params.known_association,
                             k < params.map_history_runs ? params.map_snapshots : 0);
  } catch (const NumericalError& e) {
    throw NumericalError("run " + std::to_string(k) + " of seed " + std::to_string(params.seed) +
                         ": " + e.what());
  }
}

}  // namespace

MonteCarloResult RunMonteCarlo(const ScenarioParams& scenario,
                               const LandmarkFilterFactory& make_filter,
                               const MonteCarloParams& params) {
  if (!make_filter) throw std::invalid_argument("RunMonteCarlo: no filter factory");
  const LandmarkWorld world = internal::MakeScenarioWorld(scenario);
  return internal::RunInBatches(
      world, params, [&](int k) { return RunOne(scenario, world, make_filter, params, k); });
}

MonteCarloResult RunMonteCarlo(const ScenarioConfig& config, MonteCarloParams params) {
  params.known_association = config.ekf.known_association();
  return RunMonteCarlo(config.scenario, EkfSlamFactory(config), params);
}

}  // namespace slamkit
