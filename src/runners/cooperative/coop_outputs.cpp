// The files of `slamkit coop`.
#include <algorithm>

#include <fmt/format.h>

#include "slamkit/io/atomic_file.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/runners/cooperative/coop_study.hpp"

namespace slamkit {
namespace {

nlohmann::json VehicleJson(const CoopVehicleSummary& v, bool has_ir) {
  nlohmann::json j = {{"position_rmse_m", v.position_rmse_m},
                      {"position_rmse_aligned_m", v.position_aligned_rmse_m >= 0.0
                                                      ? nlohmann::json(v.position_aligned_rmse_m)
                                                      : nullptr},
                      {"heading_rmse_rad", v.heading_rmse_rad},
                      {"anees", v.anees},
                      {"anees_in_band", v.anees_in_band},
                      {"landmarks", v.landmarks},
                      {"map_rmse_m", v.map_rmse_m >= 0.0 ? nlohmann::json(v.map_rmse_m) : nullptr},
                      {"association_agreement", v.association_agreement >= 0.0
                                                    ? nlohmann::json(v.association_agreement)
                                                    : nullptr},
                      {"position_cov_norm_final_m2",
                       v.position_cov_norm.empty() ? 0.0 : v.position_cov_norm.back()}};
  if (has_ir) {
    j["improvement_ratio_mean_pct"] = v.improvement_ratio_mean_pct;
    j["improvement_ratio_final_pct"] = v.improvement_ratio_final_pct;
  }
  return j;
}

void WriteCovNormCsv(const std::filesystem::path& path, const CoopModeSummary& m) {
  WriteFileAtomically(path, [&m](std::ostream& os) {
    os << "t_s";
    for (std::size_t v = 0; v < m.vehicles.size(); ++v) os << ",cov_norm_" << v << "_m2";
    os << "\n";
    const std::size_t n = m.vehicles.empty() ? 0 : m.vehicles[0].t_s.size();
    for (std::size_t k = 0; k < n; ++k) {
      os << fmt::format("{:.6f}", m.vehicles[0].t_s[k]);
      for (const CoopVehicleSummary& v : m.vehicles) {
        os << ',' << (k < v.position_cov_norm.size() ? fmt::format("{:.9g}", v.position_cov_norm[k])
                                                     : std::string());
      }
      os << "\n";
    }
  });
}

}  // namespace

nlohmann::json CoopMetricsJson(const CoopStudyResult& r) {
  nlohmann::json modes = nlohmann::json::object();
  const bool has_mono = std::any_of(r.modes.begin(), r.modes.end(), [](const CoopModeSummary& m) {
    return m.mode == CoopMode::kMono;
  });
  for (const CoopModeSummary& m : r.modes) {
    nlohmann::json vehicles = nlohmann::json::array();
    double position_sum = 0.0;
    for (const CoopVehicleSummary& v : m.vehicles) {
      const bool ir = has_mono && m.mode != CoopMode::kMono && HasCovariance(m.mode);
      vehicles.push_back(VehicleJson(v, ir));
      position_sum += v.position_rmse_m;
    }
    modes[std::string(CoopModeName(m.mode))] = {
        {"vehicles", vehicles},
        {"position_rmse_mean_m", m.vehicles.empty() ? 0.0 : position_sum / double(m.vehicles.size())},
        {"anees_band", {m.band.lo, m.band.hi}},
        {"update_time_mean_s", m.update_time_mean_s},
        {"vehicle_updates", m.counts.vehicle_updates},
        {"vehicle_gated", m.counts.vehicle_gated},
        {"extended_observations", m.counts.extended},
        {"landmark_updates", m.counts.landmark_updates},
        {"landmark_dropped", m.counts.landmark_dropped}};
  }
  return {{"runs", r.runs}, {"modes", modes}, {"wall_time_s", r.wall_time_s}};
}

void WriteCoopOutputs(const std::filesystem::path& dir, const CoopStudyResult& r,
                      const nlohmann::json& params, const std::string& command) {
  nlohmann::json metrics = CoopMetricsJson(r);
  metrics["params"] = params;
  metrics["command"] = command;
  WriteJson(dir / "metrics.json", metrics);
  for (const CoopModeSummary& m : r.modes) {
    const std::filesystem::path sub = dir / std::string(CoopModeName(m.mode));
    std::filesystem::create_directories(sub);
    for (std::size_t v = 0; v < m.first_run.vehicles.size(); ++v) {
      const CoopVehicleTrace& trace = m.first_run.vehicles[v];
      WriteTumTrajectory(sub / fmt::format("trajectory_{}.tum", v), trace.estimate);
      if (m.mode != CoopMode::kDeadReckoning) {
        WriteLandmarkMapCsv(sub / fmt::format("map_{}.csv", v), trace.map);
      }
    }
    WriteCovNormCsv(sub / "cov_norm.csv", m);
  }
}

}  // namespace slamkit
