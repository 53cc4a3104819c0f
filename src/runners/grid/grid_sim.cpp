#include "slamkit/runners/grid/grid_sim.hpp"

#include <chrono>
#include <utility>

namespace slamkit {

CarmenLog LogOfSimulatedRun(GridSimRun run) {
  CarmenLog log;
  log.scans = std::move(run.scans);  // run.truth stays out of the log
  log.odometry.reserve(log.scans.size());
  for (LaserScan& scan : log.scans) {
    scan.logged_pose = scan.odometry;  // what a raw log gives: never the true pose
    log.odometry.push_back({scan.t_s, scan.odometry});
  }
  return log;
}

GridSimResult RunGridSimulation(const FloorPlan& plan, const GridSimParams& sim,
                                const Pose2& start, std::uint64_t sim_seed,
                                const GridSlamConfig& slam,
                                const std::function<void(int, int)>& progress) {
  const auto sim_start = std::chrono::steady_clock::now();
  Rng rng(sim_seed);
  GridSimRun run = SimulateGridRun(plan, sim, start, rng);
  GridSimResult result;
  result.truth = std::move(run.truth);
  const CarmenLog log = LogOfSimulatedRun(std::move(run));
  result.simulation_wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sim_start).count();

  result.slam = RunGridSlam(log, slam, progress);
  result.vs_truth = CompareWithReference(result.slam.trajectory, result.truth);
  Trajectory odometry;
  odometry.reserve(log.scans.size());
  for (const LaserScan& scan : log.scans) odometry.push_back({scan.t_s, scan.odometry});
  result.odometry_vs_truth = CompareWithReference(odometry, result.truth);
  return result;
}

nlohmann::json GridSimMetrics(const GridSimResult& result, const GridSimParams& sim,
                              std::uint64_t sim_seed, const GridSlamConfig& slam,
                              double peak_rss_mib) {
  nlohmann::json j = GridMetrics(result.slam, slam, nullptr, &result.vs_truth, peak_rss_mib);
  j["sim_seed"] = sim_seed;
  j["dt_s"] = sim.dt_s;
  j["speed_mps"] = sim.speed_mps;
  j["loops"] = sim.route.loops;
  j["simulation_wall_time_s"] = result.simulation_wall_time_s;
  j["odometry_ate_rmse_m"] = result.odometry_vs_truth.ate.rmse_m;
  j["odometry_ate_mean_m"] = result.odometry_vs_truth.ate.mean_m;
  j["odometry_ate_max_m"] = result.odometry_vs_truth.ate.max_m;
  return j;
}

}  // namespace slamkit
