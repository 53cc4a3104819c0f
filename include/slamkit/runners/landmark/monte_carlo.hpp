#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/eval/consistency.hpp"
#include "slamkit/eval/errors.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/filters/landmark_slam.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/runners/common/shard.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {

// The evaluation harness of every point-landmark SLAM filter: it drives a LandmarkSlamFilter
// over simulated runs through that interface only, then joins the filter's outputs with the
// truth the simulator returned beside its inputs.

// Builds a fresh filter for one run. Called once per run, from several threads at once.
using LandmarkFilterFactory = std::function<std::unique_ptr<LandmarkSlamFilter>()>;

// EKF-SLAM with `ekf`, the motion model of `vehicle` (its noise is the filter's Q) and the
// range-bearing sensor `sensor`.
LandmarkFilterFactory EkfSlamFactory(const EkfSlamParams& ekf, const VehicleParams& vehicle,
                                     const RangeBearingParams& sensor);
// The default of the command line: the scenario file's `ekf` section with its vehicle and sensor.
LandmarkFilterFactory EkfSlamFactory(const ScenarioConfig& config);
// FastSLAM (1.0 or 2.0, as `fastslam` says) with the same inputs as EkfSlamFactory. Every filter
// it builds has `fastslam.seed`: Monte Carlo runs differ through their simulated noise.
LandmarkFilterFactory FastSlamFactory(const FastSlamParams& fastslam, const VehicleParams& vehicle,
                                      const RangeBearingParams& sensor);

// One filter run on a simulated scenario, with its errors against the truth.
struct RunResult {
  Trajectory truth;
  Trajectory estimate;
  std::vector<Eigen::Vector3d> errors;  // estimate ⊖ truth per step
  std::vector<double> nees;             // pose NEES per step (3 DoF)
  std::vector<Eigen::Matrix3d> pose_covariance;  // the filter's per step (x, y, θ)
  std::vector<double> step_time_s;      // wall time of predict + update per step
  // The filter's map over the run, when asked for (RunLandmarkFilter's map_snapshots).
  std::vector<LandmarkMapSnapshot> map_history;
  // The filter's map, with each landmark's source_id set by the harness to the true id of the
  // sighting that created it (kNoLandmark if the harness saw no sighting create it).
  LandmarkMap map;
  PoseRmse rmse;
  double map_rmse_m = 0.0;              // landmark error after the best rigid alignment
  AssociationScore association;
  std::vector<FilterCounter> counters;  // the filter's, at the end of the run
};

// Runs `filter` once over `sim`'s inputs (the true ids copied into the observations only with
// `known_association`), steps of `dt_s`, then scores it against `sim`'s truth and `world`.
// Throws std::logic_error if the filter breaks the interface (a decision count that differs from
// the observation count, a created landmark outside its map).
// With `map_snapshots` > 0 the run also keeps that many to twice as many snapshots of the
// filter's map, evenly over its steps, and the final one (RunResult::map_history).
RunResult RunLandmarkFilter(LandmarkSlamFilter& filter, const SimRun& sim,
                            const LandmarkWorld& world, double dt_s, bool known_association,
                            int map_snapshots = 0);

// What the outputs keep of one run (metrics.json's per_run).
struct RunSummary {
  PoseRmse rmse;
  double anees = 0.0;  // mean over the steps with a finite pose NEES
  int nees_infinite_steps = 0;  // steps whose pose covariance ruled out the error (eval Nees)
  std::size_t landmarks_mapped = 0;
  double map_rmse_m = 0.0;
  AssociationScore association;
  double step_time_mean_s = 0.0;
  double step_time_max_s = 0.0;
  std::vector<FilterCounter> counters;
};

// What the aggregates of a study take from one run: enough to rebuild them exactly from the
// run's saved outputs (errors.csv and its per_run entry).
struct RunRecord {
  std::vector<double> t_s;  // each step's time (the truth's, after the start)
  std::vector<Eigen::Vector3d> errors;
  std::vector<double> nees;
  PoseRmse rmse;
  std::size_t landmarks_mapped = 0;
  double map_rmse_m = 0.0;
  AssociationScore association;
  double step_time_sum_s = 0.0;
  double step_time_max_s = 0.0;
  std::size_t steps_timed = 0;
};

struct MonteCarloParams {
  int runs = 50;
  // Run only this shard's range of the runs (each with its own index's streams, so the shards'
  // runs are the unsharded study's; MergeMonteCarloShards joins them).
  Shard shard;
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all the CPUs this process may use (UsableCpuCount)
  // Give the filter the simulator's true landmark ids with each observation.
  bool known_association = false;
  // Called after each finished run with (finished, total), from worker threads one at a time.
  std::function<void(int, int)> progress;
  // Keep every RunResult in MonteCarloResult::runs. Without it only the first run (first_run) is kept.
  bool keep_runs = true;
  // Keep every RunSummary in MonteCarloResult::summaries. Without it, and without keep_runs,
  // memory is flat in the number of runs: on_run is then the only place a run is seen.
  bool keep_summaries = true;
  // Called with (k, run k, its summary) for every run, in index order, from the calling thread,
  // as soon as the batch holding run k has finished: per-run outputs are written here.
  std::function<void(int, const RunResult&, const RunSummary&)> on_run;
  // Runs simulated in parallel before they are aggregated and dropped (memory holds one batch).
  int batch_runs = 64;
  // Runs 0 .. map_history_runs - 1 keep map_snapshots to 2 × map_snapshots snapshots of their
  // map for the replay viewer (RunResult::map_history); the others keep none, so the outputs
  // stay small.
  int map_history_runs = 1;
  int map_snapshots = 40;
};

// Aggregates over runs. Per-step series are over the runs still running at that step: in the
// open loop every run has the same length (all runs share the true trajectory: noise enters
// through the controls and the sensor, never the true vehicle); in a closed loop
// (active_monte_carlo.hpp) a run that detours is longer, and the tail of a series is a mean over
// fewer runs (runs_at_step says how many).
struct MonteCarloResult {
  LandmarkWorld world;
  int run_count = 0;
  std::vector<RunResult> runs;          // every run with MonteCarloParams::keep_runs, else empty
  RunResult first_run;                  // run 0, or a shard's first (the figures draw it)
  std::vector<RunSummary> summaries;    // one per run, in index order, with keep_summaries
  std::vector<double> t_s;              // the steps of the longest run
  std::vector<int> runs_at_step;        // runs that reached each step
  std::vector<double> anees;            // mean NEES over those runs at each step
  std::vector<double> position_rmse_m;  // over those runs at each step
  std::vector<double> heading_rmse_rad;
  ChiSquareBand band;                   // 95 % band of one step's ANEES over all the runs
  double anees_mean = 0.0;              // ANEES averaged over the steps where it is finite
  int anees_infinite_steps = 0;         // steps where a run's covariance ruled out its error
  // Share of steps whose ANEES is inside the 95 % band of a mean over runs_at_step runs (`band`
  // where every run reached the step).
  double anees_fraction_in_band = 0.0;
  PoseRmse rmse;  // RMS over runs of each run's RMS
  double landmarks_mapped_mean = 0.0;
  double map_rmse_mean_m = 0.0;         // mean over runs
  double step_time_mean_s = 0.0;
  double step_time_max_s = 0.0;
  AssociationScore association;         // summed over runs
};

// Runs `params.runs` independent runs of `scenario` in parallel, each on a filter from
// `make_filter`, aggregating them as they finish (in batches of params.batch_runs, in index
// order). A world beyond WorldSpec::max_landmarks is an InputError. Run k simulates with noise from Rng::ForStream(seed, k) and observation order
// from another stream of the same seed, so the result is identical for any thread count (wall
// times aside).
MonteCarloResult RunMonteCarlo(const ScenarioParams& scenario,
                               const LandmarkFilterFactory& make_filter,
                               const MonteCarloParams& params);

// The same with EkfSlamFactory(config); known association as config.ekf says (it replaces
// params.known_association, so that the EKF and the harness agree).
MonteCarloResult RunMonteCarlo(const ScenarioConfig& config, MonteCarloParams params);

}  // namespace slamkit
