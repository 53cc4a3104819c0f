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

nlohmann::json RunJson(int k, const RunResult& r) {
  double nees_mean = 0.0, time_sum = 0.0, time_max = 0.0;
  for (double v : r.nees) nees_mean += v / static_cast<double>(r.nees.size());
  for (double t : r.step_time_s) {
    time_sum += t;
    time_max = std::max(time_max, t);
  }
  return {{"run", k},
          {"position_rmse_m", r.rmse.position_m},
          {"heading_rmse_rad", r.rmse.heading_rad},
          {"anees", nees_mean},
          {"landmarks_mapped", r.map.landmarks.size()},
          {"map_rmse_m", r.map_rmse_m},
          {"association", AssociationJson(r.association)},
          {"step_time_mean_s", r.step_time_s.empty() ? 0.0 : time_sum / r.step_time_s.size()},
          {"step_time_max_s", time_max}};
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
  for (std::size_t k = 0; k < mc.runs.size(); ++k) per_run.push_back(RunJson(int(k), mc.runs[k]));
  double map_rmse = 0.0;
  for (const RunResult& r : mc.runs) map_rmse += r.map_rmse_m / double(mc.runs.size());
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
          {"map_rmse_m", map_rmse},
          {"association", AssociationJson(mc.association)},
          {"step_time_mean_s", mc.step_time_mean_s},
          {"step_time_max_s", mc.step_time_max_s},
          {"per_run", per_run}};
}

void WriteMonteCarloOutputs(const std::filesystem::path& dir, const nlohmann::json& metrics,
                            const MonteCarloResult& mc) {
  std::filesystem::create_directories(dir);
  for (std::size_t k = 0; k < mc.runs.size(); ++k) {
    const std::filesystem::path run_dir = dir / fmt::format("run_{}", k);
    std::filesystem::create_directories(run_dir);
    WriteTumTrajectory(run_dir / "estimate.tum", mc.runs[k].estimate);
    WriteTumTrajectory(run_dir / "truth.tum", mc.runs[k].truth);
    WriteLandmarkMapCsv(run_dir / "map.csv", mc.runs[k].map);
    WriteErrorsCsv(run_dir / "errors.csv", mc.runs[k]);
  }
  WriteLandmarkWorldCsv(dir / "world.csv", mc.world);
  WriteConsistencyCsv(dir / "consistency.csv", mc);
  WriteJson(dir / "metrics.json", metrics);  // last: its presence means the run completed
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
