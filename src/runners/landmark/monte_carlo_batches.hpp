// The batch loop and the aggregation shared by the open-loop and closed-loop Monte Carlo runners
// (monte_carlo.cpp, active_monte_carlo.cpp): private to the runners module.
#pragma once

#include <cstdint>
#include <functional>

#include "slamkit/core/landmark_world.hpp"
#include "slamkit/runners/landmark/monte_carlo.hpp"
#include "slamkit/sim/scenario.hpp"

namespace slamkit::internal {

// Run k draws its noise from stream k of the seed and its observation order from stream
// kObservationOrderStreams + k, and a closed loop's planner from kPlannerStreams + k: far apart,
// so that no two runs or uses share a stream.
constexpr std::uint64_t kObservationOrderStreams = std::uint64_t{1} << 62;
constexpr std::uint64_t kPlannerStreams = std::uint64_t{2} << 62;

// The scenario's world; a world beyond WorldSpec::max_landmarks or a bad spec is an InputError
// naming the scenario.
LandmarkWorld MakeScenarioWorld(const ScenarioParams& scenario);

RunSummary SummaryOf(const RunResult& r);

// Runs run_one(k) for k in [0, params.runs) in parallel batches of params.batch_runs on
// params.threads threads and aggregates each batch in index order (then hands each run to
// params.on_run and drops it), so the result is the same for any thread count. `run_one` is
// called from worker threads. Throws std::invalid_argument for runs or batch_runs < 1.
MonteCarloResult RunInBatches(LandmarkWorld world, const MonteCarloParams& params,
                              const std::function<RunResult(int)>& run_one);

}  // namespace slamkit::internal
