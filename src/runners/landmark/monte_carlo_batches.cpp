#include "monte_carlo_batches.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

#include "../common/ordered_batches.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit::internal {
namespace {

void AddScore(AssociationScore& total, const AssociationScore& s) {
  total.sightings += s.sightings;
  total.matched += s.matched;
  total.correct += s.correct;
  total.matchable += s.matchable;
  total.created += s.created;
  total.dropped += s.dropped;
}

// Run k, in index order: aggregated, handed to on_run, then kept or dropped.
void TakeRun(int k, int first, RunResult r, const MonteCarloParams& params,
             RunAggregator& aggregate, MonteCarloResult& mc) {
  aggregate.Add(RecordOf(r));
  const RunSummary summary = SummaryOf(r);
  if (params.on_run) params.on_run(k, r, summary);
  if (params.keep_summaries) mc.summaries.push_back(summary);
  if (params.keep_runs) {
    mc.runs.push_back(std::move(r));
  } else if (k == first) {
    mc.first_run = std::move(r);
  }
}

}  // namespace

RunRecord RecordOf(const RunResult& r) {
  RunRecord record;
  for (std::size_t i = 1; i < r.truth.size(); ++i) record.t_s.push_back(r.truth[i].t_s);
  record.errors = r.errors;
  record.nees = r.nees;
  record.rmse = r.rmse;
  record.landmarks_mapped = r.map.landmarks.size();
  record.map_rmse_m = r.map_rmse_m;
  record.association = r.association;
  for (double t : r.step_time_s) {
    record.step_time_sum_s += t;
    record.step_time_max_s = std::max(record.step_time_max_s, t);
  }
  record.steps_timed = r.step_time_s.size();
  return record;
}

RunAggregator::RunAggregator(MonteCarloResult& mc, int runs)
    : mc_(mc), runs_(static_cast<double>(runs)) {
  mc_.run_count = runs;
  mc_.band = AneesBand(runs, 3);
}

void RunAggregator::Add(const RunRecord& r) {
  const std::size_t steps = r.nees.size();
  if (steps > mc_.anees.size()) Grow(r);
  for (std::size_t k = 0; k < steps; ++k) {
    mc_.anees[k] += r.nees[k];
    mc_.position_rmse_m[k] += r.errors[k].head<2>().squaredNorm();
    mc_.heading_rmse_rad[k] += r.errors[k].z() * r.errors[k].z();
    ++mc_.runs_at_step[k];
  }
  pos_sq_ += r.rmse.position_m * r.rmse.position_m;
  head_sq_ += r.rmse.heading_rad * r.rmse.heading_rad;
  time_sum_ += r.step_time_sum_s;
  mc_.step_time_max_s = std::max(mc_.step_time_max_s, r.step_time_max_s);
  time_count_ += r.steps_timed;
  mapped_ += static_cast<double>(r.landmarks_mapped);
  map_rmse_sum_ += r.map_rmse_m;
  AddScore(mc_.association, r.association);
}

void RunAggregator::Finish() {
  const std::size_t steps = mc_.anees.size();
  int inside = 0;
  for (std::size_t k = 0; k < steps; ++k) {
    const int n = mc_.runs_at_step[k];
    mc_.anees[k] /= n;
    mc_.position_rmse_m[k] = std::sqrt(mc_.position_rmse_m[k] / n);
    mc_.heading_rmse_rad[k] = std::sqrt(mc_.heading_rmse_rad[k] / n);
    if (std::isfinite(mc_.anees[k])) {
      mc_.anees_mean += mc_.anees[k];
    } else {
      ++mc_.anees_infinite_steps;
    }
    inside += BandOf(n).Contains(mc_.anees[k]) ? 1 : 0;
  }
  const std::size_t finite = steps - static_cast<std::size_t>(mc_.anees_infinite_steps);
  mc_.anees_mean = finite > 0 ? mc_.anees_mean / static_cast<double>(finite) : 0.0;
  mc_.anees_fraction_in_band = steps > 0 ? double(inside) / double(steps) : 0.0;
  mc_.rmse = {std::sqrt(pos_sq_ / runs_), std::sqrt(head_sq_ / runs_)};
  mc_.landmarks_mapped_mean = mapped_ / runs_;
  mc_.map_rmse_mean_m = map_rmse_sum_ / runs_;
  mc_.step_time_mean_s = time_count_ > 0 ? time_sum_ / double(time_count_) : 0.0;
}

void RunAggregator::Grow(const RunRecord& r) {
  const std::size_t steps = r.nees.size();
  mc_.anees.resize(steps, 0.0);
  mc_.position_rmse_m.resize(steps, 0.0);
  mc_.heading_rmse_rad.resize(steps, 0.0);
  mc_.runs_at_step.resize(steps, 0);
  for (std::size_t i = mc_.t_s.size(); i < r.t_s.size(); ++i) mc_.t_s.push_back(r.t_s[i]);
}

const ChiSquareBand& RunAggregator::BandOf(int n) {
  auto it = bands_.find(n);
  if (it == bands_.end()) it = bands_.emplace(n, AneesBand(n, 3)).first;
  return it->second;
}

LandmarkWorld MakeScenarioWorld(const ScenarioParams& scenario) {
  try {
    return MakeWorld(scenario.world);
  } catch (const std::length_error& e) {  // a world beyond WorldSpec::max_landmarks
    throw InputError("scenario " + scenario.name + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError("scenario " + scenario.name + ": " + e.what());
  }
}

RunSummary SummaryOf(const RunResult& r) {
  RunSummary s;
  std::size_t finite = 0;
  for (double v : r.nees) {
    if (std::isfinite(v)) {
      s.anees += v;
      ++finite;
    }
  }
  s.anees = finite > 0 ? s.anees / static_cast<double>(finite) : 0.0;
  s.nees_infinite_steps = static_cast<int>(r.nees.size() - finite);
  double time_sum = 0.0;
  for (double t : r.step_time_s) {
    time_sum += t;
    s.step_time_max_s = std::max(s.step_time_max_s, t);
  }
  s.step_time_mean_s = r.step_time_s.empty() ? 0.0 : time_sum / double(r.step_time_s.size());
  s.rmse = r.rmse;
  s.landmarks_mapped = r.map.landmarks.size();
  s.map_rmse_m = r.map_rmse_m;
  s.association = r.association;
  s.counters = r.counters;
  return s;
}

MonteCarloResult RunInBatches(LandmarkWorld world, const MonteCarloParams& params,
                              const std::function<RunResult(int)>& run_one) {
  if (params.runs < 1) throw std::invalid_argument("RunMonteCarlo: runs must be >= 1");
  if (params.batch_runs < 1) throw std::invalid_argument("RunMonteCarlo: batch_runs must be >= 1");
  const ShardRange range = RangeOfShard(params.runs, params.shard);
  MonteCarloResult mc;
  mc.world = std::move(world);
  if (params.keep_summaries) mc.summaries.reserve(static_cast<std::size_t>(range.size()));
  if (params.keep_runs) mc.runs.reserve(static_cast<std::size_t>(range.size()));
  RunAggregator aggregate(mc, range.size());
  OrderedBatchParams batches;
  batches.runs = range.end;
  batches.first = range.begin;
  batches.batch_runs = params.batch_runs;
  batches.threads = params.threads;
  batches.progress = params.progress;
  RunInOrderedBatches<RunResult>(batches, run_one, [&](int k, RunResult&& r) {
    TakeRun(k, range.begin, std::move(r), params, aggregate, mc);
  });
  if (params.keep_runs) mc.first_run = mc.runs.front();
  aggregate.Finish();
  return mc;
}

}  // namespace slamkit::internal
