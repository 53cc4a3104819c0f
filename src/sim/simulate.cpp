#include <optional>
#include <stdexcept>
#include <utility>

#include "slamkit/sim/scenario.hpp"
#include "slamkit/sim/simulator.hpp"

namespace slamkit {

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
  Simulator sim(scenario, world, noise_rng, order_rng);
  SimRun run;
  run.inputs.initial_pose = scenario.initial_pose;
  run.inputs.initial_observations = sim.InitialObservations();
  run.truth.initial_ids = sim.InitialIds();
  run.truth.poses.push_back({0.0, scenario.initial_pose});
  while (std::optional<SimStepWithTruth> step = sim.Step()) {
    run.truth.poses.push_back(step->truth);
    run.truth.ids.push_back(std::move(step->ids));
    run.inputs.steps.push_back(std::move(step->inputs));
  }
  return run;
}

}  // namespace slamkit
