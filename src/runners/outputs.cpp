#include "slamkit/runners/outputs.hpp"

#include <fmt/format.h>

#include "slamkit/io/atomic_file.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/models/vehicle.hpp"

namespace slamkit {
namespace {

nlohmann::json AssociationJson(const AssociationScore& s) {
  return {{"sightings", s.sightings}, {"matched", s.matched},   {"correct", s.correct},
          {"matchable", s.matchable}, {"created", s.created},   {"dropped", s.dropped},
          {"precision", s.Precision()}, {"recall", s.Recall()}};
}

nlohmann::json RunJson(int k, const RunSummary& r) {
  return {{"run", k},
          {"position_rmse_m", r.rmse.position_m},
          {"heading_rmse_rad", r.rmse.heading_rad},
          {"anees", r.anees},
          {"landmarks_mapped", r.landmarks_mapped},
          {"map_rmse_m", r.map_rmse_m},
          {"association", AssociationJson(r.association)},
          {"step_time_mean_s", r.step_time_mean_s},
          {"step_time_max_s", r.step_time_max_s}};
}

void WriteConsistencyCsv(const std::filesystem::path& path, const MonteCarloResult& mc) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "t_s,anees,position_rmse_m,heading_rmse_rad\n";
    for (std::size_t k = 0; k < mc.t_s.size(); ++k) {
      out << fmt::format("{:.6f},{:.17g},{:.17g},{:.17g}\n", mc.t_s[k], mc.anees[k],
                         mc.position_rmse_m[k], mc.heading_rmse_rad[k]);
    }
  });
}

void WriteErrorsCsv(const std::filesystem::path& path, const RunResult& r) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "t_s,error_x_m,error_y_m,error_theta_rad,nees\n";
    for (std::size_t k = 0; k < r.errors.size(); ++k) {
      out << fmt::format("{:.6f},{:.17g},{:.17g},{:.17g},{:.17g}\n", r.truth[k + 1].t_s,
                         r.errors[k].x(), r.errors[k].y(), r.errors[k].z(), r.nees[k]);
    }
  });
}

}  // namespace

nlohmann::json MonteCarloMetrics(const ScenarioConfig& config, const MonteCarloParams& params,
                                 const MonteCarloResult& mc) {
  nlohmann::json per_run = nlohmann::json::array();
  for (std::size_t k = 0; k < mc.summaries.size(); ++k) {
    per_run.push_back(RunJson(int(k), mc.summaries[k]));
  }
  const ScenarioParams& scenario = config.scenario;
  return {{"scenario", scenario.name},
          {"motion_model", ToString(scenario.vehicle.kind)},
          {"known_association", config.ekf.known_association()},
          {"runs", params.runs},
          {"seed", params.seed},
          {"steps", mc.t_s.size()},
          {"landmarks_in_world", mc.world.landmarks.size()},
          {"position_rmse_m", mc.rmse.position_m},
          {"heading_rmse_rad", mc.rmse.heading_rad},
          {"anees", mc.anees_mean},
          {"anees_band", {mc.band.lo, mc.band.hi}},
          {"anees_fraction_in_band", mc.anees_fraction_in_band},
          {"landmarks_mapped", mc.landmarks_mapped_mean},
          {"map_rmse_m", mc.map_rmse_mean_m},
          {"association", AssociationJson(mc.association)},
          {"step_time_mean_s", mc.step_time_mean_s},
          {"step_time_max_s", mc.step_time_max_s},
          {"per_run", per_run}};
}

void WriteMonteCarloOutputs(const std::filesystem::path& dir, const nlohmann::json& metrics,
                            const MonteCarloResult& mc) {
  std::filesystem::create_directories(dir);
  for (std::size_t k = 0; k < mc.runs.size(); ++k) WriteMonteCarloRun(dir, int(k), mc.runs[k]);
  WriteLandmarkWorldCsv(dir / "world.csv", mc.world);
  WriteConsistencyCsv(dir / "consistency.csv", mc);
  WriteJson(dir / "metrics.json", metrics);  // last: its presence means the run completed
}

void WriteMonteCarloRun(const std::filesystem::path& dir, int k, const RunResult& run) {
  const std::filesystem::path run_dir = dir / fmt::format("run_{}", k);
  std::filesystem::create_directories(run_dir);
  WriteTumTrajectory(run_dir / "estimate.tum", run.estimate);
  WriteTumTrajectory(run_dir / "truth.tum", run.truth);
  WriteLandmarkMapCsv(run_dir / "map.csv", run.map);
  WriteErrorsCsv(run_dir / "errors.csv", run);
}

nlohmann::json IsamMetrics(const IsamRunResult& r, const IsamRunParams& params) {
  return {{"known_association", params.ekf.known_association()},
          {"poses", r.estimate.size()},
          {"sightings", r.sightings},
          {"dropped", r.dropped},
          {"association_agreement", r.association_agreement},
          {"landmarks_mapped", r.map.landmarks.size()},
          {"odometry_covariance_scale", params.odometry_covariance_scale},
          {"sighting_covariance_scale", params.sighting_covariance_scale},
          {"wall_time_s", r.wall_time_s}};
}

void WriteIsamOutputs(const std::filesystem::path& dir, const nlohmann::json& metrics,
                      const IsamRunResult& result) {
  std::filesystem::create_directories(dir);
  WriteTumTrajectory(dir / "estimate.tum", result.estimate);
  WriteLandmarkMapCsv(dir / "map.csv", result.map);
  WriteJson(dir / "metrics.json", metrics);
}

}  // namespace slamkit
