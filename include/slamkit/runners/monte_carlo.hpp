#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/eval/consistency.hpp"
#include "slamkit/eval/errors.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/runners/scenario_config.hpp"

namespace slamkit {

// One EKF-SLAM run on a simulated scenario, with its errors against the truth.
struct RunResult {
  Trajectory truth;
  Trajectory estimate;
  std::vector<Eigen::Vector3d> errors;  // estimate ⊖ truth per step
  std::vector<double> nees;             // pose NEES per step (3 DoF)
  std::vector<double> step_time_s;      // wall time of predict + update per step
  LandmarkMap map;
  PoseRmse rmse;
  double map_rmse_m = 0.0;              // landmark error after the best rigid alignment
  AssociationScore association;
};

// Runs EKF-SLAM once over a simulated run of `scenario` in `world`, drawing noise from `rng`.
RunResult RunEkfSlamOnce(const ScenarioConfig& config, const LandmarkWorld& world, Rng& rng);

struct MonteCarloParams {
  int runs = 50;
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all hardware threads
  // Called after each finished run with (finished, total), from worker threads one at a time.
  std::function<void(int, int)> progress;
};

// Aggregates over runs. Per-step series are over the runs (all runs share the true trajectory:
// noise enters through the controls and the sensor, never the true vehicle).
struct MonteCarloResult {
  LandmarkWorld world;
  std::vector<RunResult> runs;
  std::vector<double> t_s;
  std::vector<double> anees;            // mean NEES over runs at each step
  std::vector<double> position_rmse_m;  // over runs at each step
  std::vector<double> heading_rmse_rad;
  ChiSquareBand band;                   // 95 % band of one step's ANEES
  double anees_mean = 0.0;              // ANEES averaged over steps
  double anees_fraction_in_band = 0.0;  // share of steps whose ANEES is inside the band
  PoseRmse rmse;                        // over all runs and steps
  double landmarks_mapped_mean = 0.0;
  double step_time_mean_s = 0.0;
  double step_time_max_s = 0.0;
  AssociationScore association;         // summed over runs
};

// Runs `params.runs` independent runs in parallel. Run k draws from Rng::ForStream(seed, k), so the
// result is identical for any thread count (wall times aside).
MonteCarloResult RunMonteCarlo(const ScenarioConfig& config, const MonteCarloParams& params);

}  // namespace slamkit
