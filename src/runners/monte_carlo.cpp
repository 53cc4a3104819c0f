#include "slamkit/runners/monte_carlo.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "slamkit/core/cpu.hpp"
#include "slamkit/core/numerical_error.hpp"
#include "slamkit/filters/ekf_slam.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/runners/landmark_run.hpp"

namespace slamkit {
namespace {

// Run k's observation order is drawn from stream kObservationOrderStreams + k of the seed, far
// from the noise streams 0, 1, ... of the runs.
constexpr std::uint64_t kObservationOrderStreams = std::uint64_t{1} << 62;

}  // namespace

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
                            const LandmarkWorld& world, double dt_s, bool known_association) {
  const SimInputs& inputs = sim.inputs;
  const Trajectory& truth = sim.truth.poses;
  if (truth.size() != inputs.steps.size() + 1 || sim.truth.ids.size() != inputs.steps.size()) {
    throw std::invalid_argument("RunLandmarkFilter: truth and inputs differ in length");
  }
  LandmarkRunRecorder recorder(filter, known_association);
  recorder.Start(inputs.initial_pose, truth[0], inputs.initial_observations,
                 sim.truth.initial_ids);
  for (std::size_t k = 0; k < inputs.steps.size(); ++k) {
    recorder.Step(inputs.steps[k], dt_s, truth[k + 1], sim.truth.ids[k]);
  }
  return recorder.Finish(world);
}

namespace {

void AddScore(AssociationScore& total, const AssociationScore& s) {
  total.sightings += s.sightings;
  total.matched += s.matched;
  total.correct += s.correct;
  total.matchable += s.matchable;
  total.created += s.created;
  total.dropped += s.dropped;
}

// Per-step sums over runs, added one run at a time in index order (so the sums do not depend
// on which thread finished first, and are bit for bit those of a pass over all runs), then the
// summary figures.
class Aggregator {
 public:
  Aggregator(MonteCarloResult& mc, int runs) : mc_(mc), runs_(static_cast<double>(runs)) {}

  void Add(const RunResult& r) {
    if (count_ == 0) {
      steps_ = r.nees.size();
      mc_.anees.assign(steps_, 0.0);
      mc_.position_rmse_m.assign(steps_, 0.0);
      mc_.heading_rmse_rad.assign(steps_, 0.0);
    }
    for (std::size_t k = 0; k < steps_; ++k) {
      mc_.anees[k] += r.nees[k] / runs_;
      mc_.position_rmse_m[k] += r.errors[k].head<2>().squaredNorm() / runs_;
      mc_.heading_rmse_rad[k] += r.errors[k].z() * r.errors[k].z() / runs_;
    }
    pos_sq_ += r.rmse.position_m * r.rmse.position_m;
    head_sq_ += r.rmse.heading_rad * r.rmse.heading_rad;
    for (double t : r.step_time_s) {
      time_sum_ += t;
      mc_.step_time_max_s = std::max(mc_.step_time_max_s, t);
    }
    time_count_ += r.step_time_s.size();
    mapped_ += static_cast<double>(r.map.landmarks.size());
    mc_.map_rmse_mean_m += r.map_rmse_m / runs_;
    AddScore(mc_.association, r.association);
    ++count_;
  }

  void Finish() {
    int inside = 0;
    for (std::size_t k = 0; k < steps_; ++k) {
      mc_.position_rmse_m[k] = std::sqrt(mc_.position_rmse_m[k]);
      mc_.heading_rmse_rad[k] = std::sqrt(mc_.heading_rmse_rad[k]);
      if (std::isfinite(mc_.anees[k])) {
        mc_.anees_mean += mc_.anees[k];
      } else {
        ++mc_.anees_infinite_steps;
      }
      inside += mc_.band.Contains(mc_.anees[k]) ? 1 : 0;
    }
    const std::size_t finite = steps_ - static_cast<std::size_t>(mc_.anees_infinite_steps);
    mc_.anees_mean = finite > 0 ? mc_.anees_mean / static_cast<double>(finite) : 0.0;
    mc_.anees_fraction_in_band = steps_ > 0 ? double(inside) / double(steps_) : 0.0;
    mc_.rmse = {std::sqrt(pos_sq_ / runs_), std::sqrt(head_sq_ / runs_)};
    mc_.landmarks_mapped_mean = mapped_ / runs_;
    mc_.step_time_mean_s = time_count_ > 0 ? time_sum_ / double(time_count_) : 0.0;
  }

 private:
  MonteCarloResult& mc_;
  double runs_;
  std::size_t steps_ = 0;
  std::size_t count_ = 0;
  double pos_sq_ = 0.0, head_sq_ = 0.0, time_sum_ = 0.0, mapped_ = 0.0;
  std::size_t time_count_ = 0;
};

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
  return s;
}

// Run k of a Monte Carlo set: its simulation, from its own streams of the seed, and its filter. A
// numerical failure names the run, so that it can be reproduced alone.
RunResult RunOne(const ScenarioParams& scenario, const LandmarkWorld& world,
                 const LandmarkFilterFactory& make_filter, const MonteCarloParams& params, int k) {
  const auto run = static_cast<std::uint64_t>(k);
  Rng noise_rng = Rng::ForStream(params.seed, run);
  Rng order_rng = Rng::ForStream(params.seed, kObservationOrderStreams + run);
  const SimRun sim = Simulate(scenario, world, noise_rng, order_rng);
  const std::unique_ptr<LandmarkSlamFilter> filter = make_filter();
  try {
    return RunLandmarkFilter(*filter, sim, world, scenario.dt_s, params.known_association);
  } catch (const NumericalError& e) {
    throw NumericalError("run " + std::to_string(k) + " of seed " + std::to_string(params.seed) +
                         ": " + e.what());
  }
}

}  // namespace

MonteCarloResult RunMonteCarlo(const ScenarioParams& scenario,
                               const LandmarkFilterFactory& make_filter,
                               const MonteCarloParams& params) {
  if (params.runs < 1) throw std::invalid_argument("RunMonteCarlo: runs must be >= 1");
  if (!make_filter) throw std::invalid_argument("RunMonteCarlo: no filter factory");
  if (params.batch_runs < 1) throw std::invalid_argument("RunMonteCarlo: batch_runs must be >= 1");
  MonteCarloResult mc;
  try {
    mc.world = MakeWorld(scenario.world);
  } catch (const std::length_error& e) {  // a world beyond WorldSpec::max_landmarks
    throw InputError("scenario " + scenario.name + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw InputError("scenario " + scenario.name + ": " + e.what());
  }
  mc.band = AneesBand(params.runs, 3);
  mc.run_count = params.runs;
  if (params.keep_summaries) mc.summaries.reserve(static_cast<std::size_t>(params.runs));
  if (params.keep_runs) mc.runs.reserve(static_cast<std::size_t>(params.runs));
  const int threads = params.threads > 0 ? params.threads : UsableCpuCount();
  Aggregator aggregate(mc, params.runs);
  std::mutex progress_mutex;
  int finished = 0;
  tbb::task_arena arena(std::max(threads, 1));
  // Runs in batches: a batch runs in parallel, then its runs are aggregated (and handed to
  // on_run) in index order and dropped, so memory holds one batch, not every run.
  std::vector<RunResult> batch;
  for (int first = 0; first < params.runs; first += params.batch_runs) {
    const int last = std::min(params.runs, first + params.batch_runs);
    batch.assign(static_cast<std::size_t>(last - first), RunResult{});
    arena.execute([&] {
      tbb::parallel_for(first, last, [&](int k) {
        batch[static_cast<std::size_t>(k - first)] =
            RunOne(scenario, mc.world, make_filter, params, k);
        const std::lock_guard lock(progress_mutex);
        ++finished;
        if (params.progress) params.progress(finished, params.runs);
      });
    });
    for (int k = first; k < last; ++k) {
      RunResult& r = batch[static_cast<std::size_t>(k - first)];
      if (k == 0) {
        const Trajectory& truth = r.truth;
        for (std::size_t i = 1; i < truth.size(); ++i) mc.t_s.push_back(truth[i].t_s);  // [0]: start
      }
      aggregate.Add(r);
      const RunSummary summary = SummaryOf(r);
      if (params.on_run) params.on_run(k, r, summary);
      if (params.keep_summaries) mc.summaries.push_back(summary);
      if (params.keep_runs) {
        mc.runs.push_back(std::move(r));
      } else if (k == 0) {
        mc.first_run = std::move(r);
      }
    }
  }
  if (params.keep_runs) mc.first_run = mc.runs.front();
  aggregate.Finish();
  return mc;
}

MonteCarloResult RunMonteCarlo(const ScenarioConfig& config, MonteCarloParams params) {
  params.known_association = config.ekf.known_association();
  return RunMonteCarlo(config.scenario, EkfSlamFactory(config), params);
}

}  // namespace slamkit
