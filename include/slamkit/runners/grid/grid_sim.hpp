#pragma once

#include <cstdint>
#include <functional>

#include <nlohmann/json.hpp>

#include "slamkit/runners/grid/grid_run.hpp"
#include "slamkit/sim/laser_sim.hpp"

namespace slamkit {

// SPEC S4's grid SLAM in simulation: a robot driven through a floor plan (SimulateGridRun), its
// scans fed to the grid SLAM as if read from a CARMEN log, and the result compared with the truth.

// The run's inputs as a CARMEN log: the scans as they are (odometry and logged_pose both the
// noisy odometry; the truth is not copied in) and one ODOM record per scan.
CarmenLog LogOfSimulatedRun(GridSimRun run);

struct GridSimResult {
  GridRunResult slam;
  Trajectory truth;                       // one pose per scan
  ReferenceComparison vs_truth;           // the filter's trajectory (ATE after alignment, RPE)
  ReferenceComparison odometry_vs_truth;  // the raw odometry: what the filter has to beat
  double simulation_wall_time_s = 0.0;
};

// Simulates the run from `start` with Rng(sim_seed) (independent of slam.seed, so the filter's
// seed can vary on the same data), then runs the filter; `progress(done, total)` as RunGridSlam.
GridSimResult RunGridSimulation(const FloorPlan& plan, const GridSimParams& sim,
                                const Pose2& start, std::uint64_t sim_seed,
                                const GridSlamConfig& slam,
                                const std::function<void(int, int)>& progress = {});

// metrics.json of a simulated run: GridMetrics with the comparison against the truth (ate_*,
// rpe_*), plus `sim_seed`, `dt_s`, `speed_mps`, `loops`, `simulation_wall_time_s` and the
// odometry's `odometry_ate_rmse_m`, `odometry_ate_mean_m`, `odometry_ate_max_m`.
nlohmann::json GridSimMetrics(const GridSimResult& result, const GridSimParams& sim,
                              std::uint64_t sim_seed, const GridSlamConfig& slam,
                              double peak_rss_mib);

}  // namespace slamkit
