#include "landmark/mc_figures.hpp"

#include <fmt/format.h>

#include "slamkit/report/figures.hpp"

namespace slamkit::app {

void WriteMonteCarloFigures(const std::filesystem::path& dir, const std::string& scenario,
                            const ActiveMonteCarloResult& result, int first_run) {
  const MonteCarloResult& mc = result.mc;
  PathFigureData path;
  path.markers_m = result.first_trace.centres_m;
  path.markers_label = "self-detected waypoints";
  path.title = fmt::format("{}: run {}", scenario, first_run);
  path.truth = mc.first_run.truth;
  path.estimate = mc.first_run.estimate;
  path.true_landmarks = mc.world;
  path.map = mc.first_run.map;
  WritePathFigure(dir / "map.png", path);
  WriteConsistencyPng(dir, scenario, mc);
}

void WriteConsistencyPng(const std::filesystem::path& dir, const std::string& scenario,
                         const MonteCarloResult& mc) {
  ConsistencyFigureData consistency;
  consistency.title = fmt::format("{}: {} Monte Carlo runs", scenario, mc.run_count);
  consistency.t_s = mc.t_s;
  consistency.anees = mc.anees;
  consistency.band_lo = mc.band.lo;
  consistency.band_hi = mc.band.hi;
  consistency.position_rmse_m = mc.position_rmse_m;
  consistency.heading_rmse_rad = mc.heading_rmse_rad;
  WriteConsistencyFigure(dir / "consistency.png", consistency);
}

}  // namespace slamkit::app
