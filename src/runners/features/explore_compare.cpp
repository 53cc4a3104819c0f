// SPEC S1's experiment: the three correction stages on the same exploration, over many seeds.
#include "slamkit/runners/features/explore_compare.hpp"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numeric>
#include <stdexcept>

namespace slamkit {
namespace {

// One figure over the runs.
template <typename T>
Spread SpreadOfField(const std::vector<const CompareRun*>& runs, T ExploreFigures::*field) {
  std::vector<double> v;
  for (const CompareRun* r : runs) v.push_back(static_cast<double>(r->figures.*field));
  return SpreadOf(v);
}

// SPEC S1 (NEES): ANEES per step index over the runs that reached it, while at least half did:
// runs end at different steps because an exploration may finish early.
void AneesPerStep(const std::vector<const CompareRun*>& runs, ComparePolicySummary* s) {
  const int r = static_cast<int>(runs.size());
  int inside = 0;
  for (std::size_t k = 0;; ++k) {
    double sum = 0.0;
    int count = 0;
    for (const CompareRun* run : runs) {
      if (k >= run->nees.size()) continue;
      sum += run->nees[k];
      ++count;
    }
    if (count == 0 || 2 * count < r) break;
    s->anees.push_back(sum / count);
    s->anees_runs.push_back(count);
    inside += AneesBand(count, 3).Contains(s->anees.back()) ? 1 : 0;
  }
  s->band = AneesBand(std::max(r, 1), 3);
  if (s->anees.empty()) return;
  s->anees_in_band = double(inside) / double(s->anees.size());
  s->anees_mean = std::accumulate(s->anees.begin(), s->anees.end(), 0.0) / s->anees.size();
}

// SPEC S1, Eq. 24 averaged two ways: every step alike, and every run alike.
void Accuracy(const std::vector<const CompareRun*>& runs, ComparePolicySummary* s) {
  double sum = 0.0;
  int steps = 0;
  std::vector<double> per_run;
  for (const CompareRun* r : runs) {
    sum += r->accuracy_sum;
    steps += r->accuracy_steps;
    if (r->accuracy_steps > 0) per_run.push_back(r->accuracy_sum / r->accuracy_steps);
  }
  if (steps > 0) s->accuracy_step_mean = sum / steps;
  if (!per_run.empty()) s->accuracy_run_mean = SpreadOf(per_run).mean;
}

// One run: its policy and seed in `config`. Selection diagnostics on for the accuracy ratio in
// modelled timing (they work on a marginal of the filter, so the path and the modelled cost stay
// those without); off in wall timing, where their extra full update would be measured too.
CompareRun RunOne(const FloorPlan& plan, ExplorationConfig config, SelectionKind policy,
                  std::uint64_t seed, ExploreResult* keep) {
  config.slam.selection = policy;
  config.seed = seed;
  config.slam.ekf.selection_diagnostics = config.run.timing == SlamTiming::kModelledCost;
  ExploreResult result = RunFeatureExploration(plan, config);
  CompareRun run = SummariseCompareRun(result, config);
  if (keep != nullptr) *keep = std::move(result);
  return run;
}

}  // namespace

std::vector<std::uint64_t> ExploreCompareParams::DefaultCompareSeeds() {
  std::vector<std::uint64_t> seeds(20);
  std::iota(seeds.begin(), seeds.end(), 1);
  return seeds;
}

CompareRun SummariseCompareRun(const ExploreResult& result, const ExplorationConfig& config) {
  CompareRun run;
  run.policy = config.slam.selection;
  run.seed = config.seed;
  run.figures = ExploreFiguresOf(result);
  run.nees = result.nees;
  for (const std::optional<double>& a : result.accuracy) {
    if (!a) continue;
    run.accuracy_sum += *a;
    ++run.accuracy_steps;
  }
  return run;
}

ComparePolicySummary SummarisePolicy(SelectionKind policy, const std::vector<CompareRun>& all) {
  std::vector<const CompareRun*> runs;
  for (const CompareRun& r : all) {
    if (r.policy == policy) runs.push_back(&r);
  }
  ComparePolicySummary s;
  s.policy = policy;
  s.runs = static_cast<int>(runs.size());
  s.slam_time_total_s = SpreadOfField(runs, &ExploreFigures::slam_time_total_s);
  const Spread max_step = SpreadOfField(runs, &ExploreFigures::slam_time_max_s);
  s.slam_time_max_mean_s = max_step.mean;
  s.slam_time_max_s = max_step.max;
  s.open_loop_time_s = SpreadOfField(runs, &ExploreFigures::open_loop_time_s);
  Accuracy(runs, &s);
  AneesPerStep(runs, &s);
  s.mean_error_m = SpreadOfField(runs, &ExploreFigures::mean_error_m);
  s.final_error_m = SpreadOfField(runs, &ExploreFigures::final_error_m);
  s.odometry_mean_error_m = SpreadOfField(runs, &ExploreFigures::odometry_mean_error_m);
  s.odometry_final_error_m = SpreadOfField(runs, &ExploreFigures::odometry_final_error_m);
  s.lines = SpreadOfField(runs, &ExploreFigures::lines);
  s.corners = SpreadOfField(runs, &ExploreFigures::corners);
  s.steps = SpreadOfField(runs, &ExploreFigures::steps);
  s.elapsed_s = SpreadOfField(runs, &ExploreFigures::elapsed_s);
  s.wall_time_s = SpreadOfField(runs, &ExploreFigures::wall_time_s);
  return s;
}

// SPEC S1's claim (33–45 % less than sequential, 47–56 % less than entropy), seed by seed.
std::vector<CovarianceSavings> CovarianceSavingsOf(const std::vector<CompareRun>& runs,
                                                   const std::vector<SelectionKind>& policies) {
  const auto total = [&runs](SelectionKind p, std::uint64_t seed) {
    for (const CompareRun& r : runs) {
      if (r.policy == p && r.seed == seed) return r.figures.slam_time_total_s;
    }
    throw std::logic_error("no run of that policy and seed");
  };
  std::vector<CovarianceSavings> out;
  if (std::find(policies.begin(), policies.end(), SelectionKind::kCovariance) == policies.end()) {
    return out;
  }
  for (const SelectionKind other : policies) {
    if (other == SelectionKind::kCovariance) continue;
    std::vector<double> per_seed, cov, oth;
    for (const CompareRun& r : runs) {
      if (r.policy != other) continue;
      cov.push_back(total(SelectionKind::kCovariance, r.seed));
      oth.push_back(r.figures.slam_time_total_s);
      per_seed.push_back(100.0 * (1.0 - cov.back() / oth.back()));
    }
    const Spread s = SpreadOf(per_seed);
    out.push_back({other, 100.0 * (1.0 - SpreadOf(cov).mean / SpreadOf(oth).mean), s.min, s.max});
  }
  return out;
}

// SPEC S1, experiments: every policy × seed. Modelled timing makes each run deterministic, so
// they may go in parallel into fixed slots; measured timing runs them one at a time.
ExploreCompareResult RunExploreCompare(const FloorPlan& plan, const ExplorationConfig& config,
                                       const ExploreCompareParams& params,
                                       const CompareProgress& progress) {
  if (params.policies.empty() || params.seeds.empty()) {
    throw std::invalid_argument("explore compare: needs at least one policy and one seed");
  }
  const auto start = std::chrono::steady_clock::now();
  const int seeds = static_cast<int>(params.seeds.size());
  const int total = static_cast<int>(params.policies.size()) * seeds;
  ExploreCompareResult out;
  out.runs.resize(total);
  out.first_seed.resize(params.policies.size());
  std::mutex mutex;
  int done = 0;
  const auto run = [&](int i) {
    ExploreResult* keep = i % seeds == 0 ? &out.first_seed[i / seeds] : nullptr;
    out.runs[i] = RunOne(plan, config, params.policies[i / seeds], params.seeds[i % seeds], keep);
    const std::lock_guard<std::mutex> lock(mutex);
    if (progress) progress(++done, total);
  };
  const bool parallel = config.run.timing == SlamTiming::kModelledCost && params.threads != 1;
  if (parallel) {
    tbb::task_arena arena(params.threads > 0 ? params.threads : tbb::task_arena::automatic);
    arena.execute([&] { tbb::parallel_for(0, total, 1, run); });
  } else {
    for (int i = 0; i < total; ++i) run(i);
  }
  for (const SelectionKind p : params.policies)
    out.policies.push_back(SummarisePolicy(p, out.runs));
  out.savings = CovarianceSavingsOf(out.runs, params.policies);
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace slamkit
