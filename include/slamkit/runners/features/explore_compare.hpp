#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "slamkit/eval/consistency.hpp"
#include "slamkit/eval/spread.hpp"
#include "slamkit/runners/features/explore_run.hpp"

namespace slamkit {

// SPEC S1's comparison of the correction stages: every policy on every seed of one experiment.
struct ExploreCompareParams {
  std::vector<SelectionKind> policies = {SelectionKind::kAll, SelectionKind::kEntropy,
                                         SelectionKind::kCovariance};
  std::vector<std::uint64_t> seeds = DefaultCompareSeeds();
  // Runs at once in `modelled` timing (0: as many as TBB's CPUs); `wall` timing always runs one
  // at a time, so that the measured SLAM times are not disturbed by each other.
  int threads = 0;

  static std::vector<std::uint64_t> DefaultCompareSeeds();  // 1 … 20
};

// What the summary keeps of one run (a policy on a seed): its figures and the per-step NEES and
// accuracy sums, not the map.
struct CompareRun {
  SelectionKind policy = SelectionKind::kCovariance;
  std::uint64_t seed = 0;
  ExploreFigures figures;
  std::vector<double> nees;    // per step from step 1, as ExploreResult::nees
  double accuracy_sum = 0.0;   // Σ of the per-step accuracy ratios (Eq. 24) over the steps
  int accuracy_steps = 0;      // that have one
};

// One policy over the seeds.
struct ComparePolicySummary {
  SelectionKind policy = SelectionKind::kCovariance;
  int runs = 0;
  Spread slam_time_total_s;
  double slam_time_max_mean_s = 0.0;  // mean over runs of each run's per-step maximum
  double slam_time_max_s = 0.0;       // the largest step of all runs
  Spread open_loop_time_s;
  std::optional<double> accuracy_step_mean;  // over all steps of all runs
  std::optional<double> accuracy_run_mean;   // of the per-run means
  // Pose ANEES (3 dof) at each step index over the runs still running, while at least half of
  // them are; anees_runs says how many, each step's band is that count's.
  std::vector<double> anees;
  std::vector<int> anees_runs;
  ChiSquareBand band;             // the 95 % band for all `runs`
  double anees_in_band = 0.0;     // share of the steps inside their band
  double anees_mean = 0.0;        // mean of `anees`
  Spread mean_error_m, final_error_m, odometry_mean_error_m, odometry_final_error_m;
  Spread lines, corners, steps, elapsed_s, wall_time_s;
};

// SPEC S1's claim: 1 − T_covariance / T_other of the accumulated SLAM time, in %: of the means,
// and the smallest and largest over seeds (run against run on the same seed).
struct CovarianceSavings {
  SelectionKind against = SelectionKind::kAll;
  double of_means_pct = 0.0;
  double min_pct = 0.0;
  double max_pct = 0.0;
};

struct ExploreCompareResult {
  std::vector<CompareRun> runs;  // policy by policy in params order, seeds in order within
  std::vector<ComparePolicySummary> policies;
  std::vector<CovarianceSavings> savings;  // empty unless covariance and another policy ran
  std::vector<ExploreResult> first_seed;   // per policy, the first seed's whole run (figures)
  double wall_time_s = 0.0;
};

// Called after each run with the number done and the total; from one thread at a time.
using CompareProgress = std::function<void(int done, int total)>;

// Runs every policy × seed of `config` (its policy and seed replaced; selection diagnostics on
// for the accuracy ratio in modelled timing, off in wall timing, where they would be measured
// as part of the step) and summarises them. The result is the same whatever `threads`, except
// wall times. Throws std::invalid_argument for no policy or no seed.
ExploreCompareResult RunExploreCompare(const FloorPlan& plan, const ExplorationConfig& config,
                                       const ExploreCompareParams& params,
                                       const CompareProgress& progress = {});

// The parts of RunExploreCompare, for tests: one run's record, and the summaries over runs.
CompareRun SummariseCompareRun(const ExploreResult& result, const ExplorationConfig& config);
ComparePolicySummary SummarisePolicy(SelectionKind policy, const std::vector<CompareRun>& runs);
std::vector<CovarianceSavings> CovarianceSavingsOf(const std::vector<CompareRun>& runs,
                                                   const std::vector<SelectionKind>& policies);

// The outputs (README, `explore --compare`): DIR/compare.md (a table, one row per policy, the
// savings and `command`), DIR/compare.csv (one row per run) and DIR/metrics.json (`params`,
// `policies`, `seeds`, `summary`, `savings`, `runs`), each written atomically.
void WriteExploreCompareOutputs(const std::filesystem::path& dir,
                                const ExploreCompareResult& result,
                                const ExplorationConfig& config,
                                const ExploreCompareParams& params, const std::string& command);
std::string ExploreCompareMarkdown(const ExploreCompareResult& result,
                                   const ExplorationConfig& config, const std::string& command);

}  // namespace slamkit
