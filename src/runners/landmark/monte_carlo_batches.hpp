// The batch loop and the aggregation shared by the open-loop and closed-loop Monte Carlo runners
// (monte_carlo.cpp, active_monte_carlo.cpp): private to the runners module.
#pragma once

#include <cstdint>
#include <functional>
#include <map>

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
RunRecord RecordOf(const RunResult& r);

// Per-step sums over the runs still running at each step (closed-loop runs differ in length),
// added one run at a time in index order so that the sums do not depend on which thread finished
// first, then the summary figures. Fed from live runs (RecordOf) or from a shard's saved
// outputs (MergeMonteCarloShards), in the same order, it gives the same figures bit for bit.
class RunAggregator {
 public:
  // Sets mc's run_count and band for `runs` runs.
  RunAggregator(MonteCarloResult& mc, int runs);
  void Add(const RunRecord& r);
  void Finish();

 private:
  void Grow(const RunRecord& r);  // a run longer than all before it: the series gain its steps
  const ChiSquareBand& BandOf(int n);  // the band of a mean over the n runs at a step

  MonteCarloResult& mc_;
  double runs_;
  double pos_sq_ = 0.0, head_sq_ = 0.0, time_sum_ = 0.0, mapped_ = 0.0, map_rmse_sum_ = 0.0;
  std::size_t time_count_ = 0;
  std::map<int, ChiSquareBand> bands_;
};

// Runs run_one(k) for k in params.shard's range of [0, params.runs) in parallel batches of params.batch_runs on
// params.threads threads and aggregates each batch in index order (then hands each run to
// params.on_run and drops it), so the result is the same for any thread count. `run_one` is
// called from worker threads. Throws std::invalid_argument for runs or batch_runs < 1.
MonteCarloResult RunInBatches(LandmarkWorld world, const MonteCarloParams& params,
                              const std::function<RunResult(int)>& run_one);

}  // namespace slamkit::internal
