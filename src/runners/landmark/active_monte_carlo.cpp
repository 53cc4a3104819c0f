#include "slamkit/runners/landmark/active_monte_carlo.hpp"

#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "monte_carlo_batches.hpp"
#include "slamkit/core/numerical_error.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

// Per-section sums over runs, added in index order (so that the means do not depend on which
// thread finished first).
class SectionSums {
 public:
  void Add(const std::vector<SectionStats>& run) {
    if (run.size() > sums_.size()) sums_.resize(run.size());
    for (std::size_t i = 0; i < run.size(); ++i) {
      SectionMean& m = sums_[i];
      const SectionStats& s = run[i];
      m.index = static_cast<int>(i);
      ++m.runs;
      m.periods += s.periods;
      m.observations += s.observations;
      m.landmarks += s.landmarks;
      m.observations_per_period += s.observations_per_period;
      m.observations_per_landmark += s.observations_per_landmark;
    }
  }

  std::vector<SectionMean> Means() const {
    std::vector<SectionMean> means = sums_;
    for (SectionMean& m : means) {  // every entry has runs >= 1: it was added to grow the list
      m.periods /= m.runs;
      m.observations /= m.runs;
      m.landmarks /= m.runs;
      m.observations_per_period /= m.runs;
      m.observations_per_landmark /= m.runs;
    }
    return means;
  }

 private:
  std::vector<SectionMean> sums_;
};

// Run k: RunMonteCarlo's noise and order streams, and a planner stream of the same seed.
ActiveRunResult RunOneActive(const ScenarioParams& scenario, const PlannerConfig& planner,
                             const LandmarkWorld& world, const LandmarkFilterFactory& make_filter,
                             const MonteCarloParams& params, int k) {
  const auto run = static_cast<std::uint64_t>(k);
  Rng noise_rng = Rng::ForStream(params.seed, run);
  Rng order_rng = Rng::ForStream(params.seed, internal::kObservationOrderStreams + run);
  Rng planner_rng = Rng::ForStream(params.seed, internal::kPlannerStreams + run);
  const std::unique_ptr<LandmarkSlamFilter> filter = make_filter();
  try {
    return RunActive(scenario, planner, world, *filter, params.known_association, noise_rng,
                     order_rng, planner_rng,
                     k < params.map_history_runs ? params.map_snapshots : 0);
  } catch (const NumericalError& e) {
    throw NumericalError("run " + std::to_string(k) + " of seed " + std::to_string(params.seed) +
                         ": " + e.what());
  }
}

ActiveRunTrace TraceOf(int k, ActiveRunResult& a, const ActiveMonteCarloParams& params) {
  ActiveRunTrace trace;
  if (params.sections_of_run) {
    for (const RouteSection& s : params.sections_of_run(k, a.period_states)) {
      trace.sections.push_back(ComputeSectionStats(s, a.period_ids));
    }
  } else {
    trace.sections = std::move(a.sections);
  }
  trace.centres_m = std::move(a.centres_m);
  trace.periods = a.periods;
  trace.steps = static_cast<int>(a.run.nees.size());
  if (params.keep_period_states) trace.period_states = std::move(a.period_states);
  return trace;
}

}  // namespace

std::vector<SectionMean> MeanSections(const std::vector<std::vector<SectionStats>>& sections) {
  SectionSums sums;
  for (const std::vector<SectionStats>& run : sections) sums.Add(run);
  return sums.Means();
}

ActiveMonteCarloResult RunActiveMonteCarlo(const ScenarioParams& scenario,
                                           const PlannerConfig& planner,
                                           const LandmarkFilterFactory& make_filter,
                                           const ActiveMonteCarloParams& params) {
  if (!make_filter) throw std::invalid_argument("RunActiveMonteCarlo: no filter factory");
  const LandmarkWorld world = internal::MakeScenarioWorld(scenario);
  ActiveMonteCarloResult result;
  result.planner = planner.kind;
  // Traces wait here from the worker that made them to their turn in index order: one batch.
  std::map<int, ActiveRunTrace> pending;
  std::mutex pending_mutex;
  SectionSums sums;
  const int first_run = RangeOfShard(params.mc.runs, params.mc.shard).begin;
  MonteCarloParams mc_params = params.mc;
  mc_params.on_run = [&](int k, const RunResult& run, const RunSummary& summary) {
    ActiveRunTrace trace;
    {
      const std::lock_guard lock(pending_mutex);
      trace = std::move(pending.at(k));
      pending.erase(k);
    }
    sums.Add(trace.sections);
    if (params.mc.on_run) params.mc.on_run(k, run, summary);
    if (params.on_run) params.on_run(k, run, summary, trace);
    if (k == first_run) result.first_trace = trace;
    if (params.keep_traces) result.traces.push_back(std::move(trace));
  };
  result.mc = internal::RunInBatches(world, mc_params, [&](int k) {
    ActiveRunResult active = RunOneActive(scenario, planner, world, make_filter, params.mc, k);
    ActiveRunTrace trace = TraceOf(k, active, params);
    const std::lock_guard lock(pending_mutex);
    pending.emplace(k, std::move(trace));
    return std::move(active.run);
  });
  result.sections = sums.Means();
  return result;
}

ActiveMonteCarloResult RunActiveMonteCarlo(const ScenarioConfig& config,
                                           const LandmarkFilterFactory& make_filter,
                                           PlannerKind kind, ActiveMonteCarloParams params) {
  PlannerConfig planner = config.planner;
  planner.kind = kind;
  params.mc.known_association = config.ekf.known_association();
  return RunActiveMonteCarlo(config.scenario, planner, make_filter, params);
}

PlannerKind ParsePlannerKind(std::string_view name) {
  for (PlannerKind kind : {PlannerKind::kRoute, PlannerKind::kSwslam}) {
    if (name == PlannerName(kind)) return kind;
  }
  throw InputError("unknown planner '" + std::string(name) + "': expected route or swslam");
}

std::string_view PlannerName(PlannerKind kind) {
  return kind == PlannerKind::kSwslam ? "swslam" : "route";
}

}  // namespace slamkit
