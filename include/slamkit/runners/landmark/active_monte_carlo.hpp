#pragma once

#include <functional>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "slamkit/runners/landmark/active_run.hpp"
#include "slamkit/runners/landmark/monte_carlo.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {

// Closed-loop Monte Carlo (SPEC S2): RunMonteCarlo's harness with every run driven by RunActive,
// so that a planner may send the vehicle off its route. Run k draws its noise and observation
// order from the streams RunMonteCarlo's run k uses and its planner's K-means from a third
// stream of the seed, so with PlannerKind::kRoute the figures are RunMonteCarlo's bit for bit.
// With SWSLAM's detours the runs differ in length: the per-step series are means over the runs
// still running at each step (MonteCarloResult::runs_at_step).

// What a closed-loop run keeps besides its RunSummary (small: a few sections and centres).
struct ActiveRunTrace {
  std::vector<SectionStats> sections;
  std::vector<Eigen::Vector2d> centres_m;  // the chosen detours, in order
  int periods = 0;                         // observation periods
  int steps = 0;
  // One per period, with ActiveMonteCarloParams::keep_period_states only.
  std::vector<PeriodState> period_states;
};

// Section i's figures averaged over the runs that have a section i (seed 001 Tables 1-3 give one
// row per section, "means over runs"). A run's sections are numbered in the order they opened,
// so section i of two runs is the i-th area of interest each detected.
struct SectionMean {
  int index = 0;
  int runs = 0;  // runs with a section i
  double periods = 0.0;
  double observations = 0.0;
  double landmarks = 0.0;
  double observations_per_period = 0.0;
  double observations_per_landmark = 0.0;
};

// `sections[k]` holds run k's sections; section i is averaged over the runs that have it.
std::vector<SectionMean> MeanSections(const std::vector<std::vector<SectionStats>>& sections);

struct ActiveMonteCarloParams {
  // Runs, seed, threads, batches, progress, known association and keep_runs/keep_summaries as
  // for RunMonteCarlo. Its on_run is called too (before this struct's on_run).
  MonteCarloParams mc;
  // Keep each run's ActiveRunTrace in ActiveMonteCarloResult::traces (else only the section
  // means are kept, and memory stays flat in the number of runs).
  bool keep_traces = true;
  // Keep one PeriodState per observation period in each kept trace (a SWSLAM run whose sections
  // route runs are measured on: CarrySections).
  bool keep_period_states = false;
  // When set, run k's section statistics are computed on the sections this returns for it from
  // the run's own period states, in place of its planner's: the study measures a route run on
  // the sections of the SWSLAM run with the same seed. Called from worker threads.
  std::function<std::vector<RouteSection>(int k, const std::vector<PeriodState>& periods)>
      sections_of_run;
  // Called with run k, its summary and its trace (period states included only with
  // keep_period_states), in index order, from the calling thread as in MonteCarloParams::on_run.
  std::function<void(int, const RunResult&, const RunSummary&, const ActiveRunTrace&)> on_run;
};

struct ActiveMonteCarloResult {
  MonteCarloResult mc;
  PlannerKind planner = PlannerKind::kRoute;
  std::vector<ActiveRunTrace> traces;  // one per run in index order, with keep_traces
  ActiveRunTrace first_trace;          // first_run's (its centres go on the map figure)
  std::vector<SectionMean> sections;   // over all runs
};

// `params.mc.runs` closed-loop runs of `scenario` with `planner`, each on a filter from
// `make_filter`, in parallel; identical for any thread count. A world beyond
// WorldSpec::max_landmarks is an InputError; a numerical failure names the run and the seed.
ActiveMonteCarloResult RunActiveMonteCarlo(const ScenarioParams& scenario,
                                           const PlannerConfig& planner,
                                           const LandmarkFilterFactory& make_filter,
                                           const ActiveMonteCarloParams& params);

// The same on a scenario file: its vehicle, sensor and world, its planner section with `kind`
// in place of the file's, and known association as its `ekf` section says (replacing
// params.mc.known_association, so that the filter and the harness agree).
ActiveMonteCarloResult RunActiveMonteCarlo(const ScenarioConfig& config,
                                           const LandmarkFilterFactory& make_filter,
                                           PlannerKind kind, ActiveMonteCarloParams params);

// "route" or "swslam"; anything else is an InputError naming the value and the choices.
PlannerKind ParsePlannerKind(std::string_view name);
std::string_view PlannerName(PlannerKind kind);

}  // namespace slamkit
