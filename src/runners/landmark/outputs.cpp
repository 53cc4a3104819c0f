#include "slamkit/runners/landmark/outputs.hpp"

#include <span>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "slamkit/io/atomic_file.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/models/vehicle.hpp"
#include "slamkit/runners/common/log_scoring.hpp"
#include "slamkit/runners/landmark/isam_config.hpp"

namespace slamkit {
namespace {

nlohmann::json AssociationJson(const AssociationScore& s) {
  return {{"sightings", s.sightings}, {"matched", s.matched},   {"correct", s.correct},
          {"matchable", s.matchable}, {"created", s.created},   {"dropped", s.dropped},
          {"precision", s.Precision()}, {"recall", s.Recall()}};
}

void WriteConsistencyCsv(const std::filesystem::path& path, const MonteCarloResult& mc) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "t_s,anees,position_rmse_m,heading_rmse_rad,runs\n";
    for (std::size_t k = 0; k < mc.t_s.size(); ++k) {
      out << fmt::format("{:.6f},{:.17g},{:.17g},{:.17g},{}\n", mc.t_s[k], mc.anees[k],
                         mc.position_rmse_m[k], mc.heading_rmse_rad[k], mc.runs_at_step[k]);
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

// Each step's pose covariance (x, y, θ; its upper triangle), for the viewer's pose ellipses:
// covariance k belongs to poses[k + 1] (the pose after step k).
void WritePoseCovarianceCsv(const std::filesystem::path& path, const Trajectory& poses,
                            const std::vector<Eigen::Matrix3d>& covariances) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "t_s,cov_xx,cov_xy,cov_xt,cov_yy,cov_yt,cov_tt\n";
    for (std::size_t k = 0; k < covariances.size(); ++k) {
      const Eigen::Matrix3d& c = covariances[k];
      out << fmt::format("{:.6f},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n",
                         poses[k + 1].t_s, c(0, 0), c(0, 1), c(0, 2), c(1, 1), c(1, 2), c(2, 2));
    }
  });
}

// `json` as dump(2) would print it inside an array inside the top-level object.
std::string IndentedEntry(const nlohmann::json& json) {
  std::string out = "    ";
  for (const char c : json.dump(2)) {
    out += c;
    if (c == '\n') out += "    ";
  }
  return out;
}

// A filter's cost figures by name ({} for a filter without any).
nlohmann::json CountersJson(std::span<const FilterCounter> counters) {
  nlohmann::json json = nlohmann::json::object();
  for (const FilterCounter& c : counters) json[c.name] = c.value;
  return json;
}

nlohmann::json InnovationCheckJson(const InnovationCheck& c) {
  return {{"sightings", c.sightings},
          {"outside_gate", c.outside_gate},
          {"reference_landmarks", c.reference_landmarks},
          {"reobservations_outside_gate_share", c.reobservations_outside_share},
          {"expected_share", c.expected_share},
          {"band_95_hi", c.band_hi},
          {"ratio", c.ratio},
          {"verdict", VerdictName(c.verdict)}};
}

}  // namespace

std::string IsamNoiseWarning(const InnovationCheck& c) {
  if (!c.warn()) return "";
  return fmt::format(
      "{:.1f} % of the sightings that re-observe a landmark (the log names {} landmarks in {} "
      "sightings) matched none, {:.0f} times the {:.1f} % that the association gate lets a right "
      "noise model miss: the filter's innovations are larger than its covariance says. The "
      "odometry or sighting noise is likely too small for this log (a file's own covariances "
      "often are, and do not grow with the motion), so re-observations start duplicate landmarks "
      "and the map and path diverge. Widen the odometry noise (odometry.srr/srt/str/stt or "
      "odometry.covariance_scale; --odometry-noise, --odometry-cov-scale) or the sighting noise "
      "(sightings.sigma_range_m/sigma_bearing_deg or sightings.covariance_scale; "
      "--sighting-noise, --sighting-cov-scale), or start from a tuned config such as "
      "configs/victoria_park.yaml",
      100.0 * c.reobservations_outside_share, c.reference_landmarks, c.sightings, c.ratio,
      100.0 * c.expected_share);
}

nlohmann::json RunSummaryJson(int k, const RunSummary& r) {
  return {{"run", k},
          {"filter_counters", CountersJson(r.counters)},
          {"position_rmse_m", r.rmse.position_m},
          {"heading_rmse_rad", r.rmse.heading_rad},
          {"anees", r.anees},
          {"nees_infinite_steps", r.nees_infinite_steps},
          {"landmarks_mapped", r.landmarks_mapped},
          {"map_rmse_m", r.map_rmse_m},
          {"association", AssociationJson(r.association)},
          {"step_time_mean_s", r.step_time_mean_s},
          {"step_time_max_s", r.step_time_max_s}};
}

nlohmann::json MonteCarloResultJson(const MonteCarloResult& mc) {
  return {{"steps", mc.t_s.size()},
          {"landmarks_in_world", mc.world.landmarks.size()},
          {"position_rmse_m", mc.rmse.position_m},
          {"heading_rmse_rad", mc.rmse.heading_rad},
          {"anees", mc.anees_mean},
          {"anees_band", {mc.band.lo, mc.band.hi}},
          {"anees_fraction_in_band", mc.anees_fraction_in_band},
          {"anees_infinite_steps", mc.anees_infinite_steps},
          {"landmarks_mapped", mc.landmarks_mapped_mean},
          {"map_rmse_m", mc.map_rmse_mean_m},
          {"association", AssociationJson(mc.association)},
          {"step_time_mean_s", mc.step_time_mean_s},
          {"step_time_max_s", mc.step_time_max_s}};
}

nlohmann::json MonteCarloMetrics(const ScenarioConfig& config, const MonteCarloParams& params,
                                 const MonteCarloResult& mc) {
  const ScenarioParams& scenario = config.scenario;
  nlohmann::json metrics = {{"scenario", scenario.name},
                            {"motion_model", ToString(scenario.vehicle.kind)},
                            {"known_association", config.ekf.known_association()},
                            {"runs", params.runs},
                            {"seed", params.seed}};
  metrics.update(MonteCarloResultJson(mc));
  metrics["params"] = ScenarioParamsJson(config);
  if (!params.shard.whole()) {
    const ShardRange range = RangeOfShard(params.runs, params.shard);
    metrics["shard"] = {{"index", params.shard.index},
                        {"count", params.shard.count},
                        {"first_run", range.begin},
                        {"end_run", range.end}};
  }
  return metrics;
}

MonteCarloWriter::MonteCarloWriter(std::filesystem::path dir)
    : dir_(std::move(dir)), scratch_path_(dir_ / ".per_run.partial") {
  std::filesystem::create_directories(dir_);
  scratch_.open(scratch_path_, std::ios::binary | std::ios::trunc);
  if (!scratch_) throw std::runtime_error("cannot write " + scratch_path_.string());
}

MonteCarloWriter::~MonteCarloWriter() {
  scratch_.close();
  std::error_code ignored;
  std::filesystem::remove(scratch_path_, ignored);
}

void MonteCarloWriter::Add(int k, const RunResult& run, const RunSummary& summary) {
  Add(k, run, summary, nlohmann::json::object());
}

void MonteCarloWriter::Add(int k, const RunResult& run, const RunSummary& summary,
                           const nlohmann::json& extra) {
  const std::filesystem::path run_dir = dir_ / fmt::format("run_{}", k);
  std::filesystem::create_directories(run_dir);
  WriteTumTrajectory(run_dir / "estimate.tum", run.estimate);
  WriteTumTrajectory(run_dir / "truth.tum", run.truth);
  WriteLandmarkMapCsv(run_dir / "map.csv", run.map);
  WriteErrorsCsv(run_dir / "errors.csv", run);
  WritePoseCovarianceCsv(run_dir / "pose_covariance.csv", run.truth, run.pose_covariance);
  if (!run.map_history.empty()) {
    WriteLandmarkMapHistoryCsv(run_dir / "map_history.csv", run.map_history);
  }
  nlohmann::json entry = RunSummaryJson(k, summary);
  entry.update(extra);
  AddEntry(entry);
}

void MonteCarloWriter::AddEntry(const nlohmann::json& entry) {
  scratch_ << (runs_ > 0 ? ",\n" : "") << IndentedEntry(entry);
  if (!scratch_) throw std::runtime_error("cannot write " + scratch_path_.string());
  ++runs_;
}

void MonteCarloWriter::Finish(const nlohmann::json& summary, const MonteCarloResult& mc) {
  WriteLandmarkWorldCsv(dir_ / "world.csv", mc.world);
  WriteConsistencyCsv(dir_ / "consistency.csv", mc);
  scratch_.close();
  if (!scratch_) throw std::runtime_error("cannot write " + scratch_path_.string());
  std::string head = summary.dump(2);  // "{\n  ...\n}": per_run goes before the closing brace
  head.pop_back();
  while (!head.empty() && head.back() == '\n') head.pop_back();
  WriteFileAtomically(dir_ / "metrics.json", [&](std::ostream& out) {
    out << head << (summary.empty() ? "" : ",") << "\n  \"per_run\": [";
    std::ifstream entries(scratch_path_, std::ios::binary);
    if (runs_ > 0) out << "\n" << entries.rdbuf() << "\n  ";
    if (!entries) throw std::runtime_error("cannot read " + scratch_path_.string());
    out << "]\n}\n";
  });
  std::filesystem::remove(scratch_path_);
}

void WriteMonteCarloOutputs(const std::filesystem::path& dir, const nlohmann::json& summary,
                            const MonteCarloResult& mc) {
  const auto runs = static_cast<std::size_t>(mc.run_count);
  if (mc.runs.size() != runs || mc.summaries.size() != runs) {
    throw std::invalid_argument("WriteMonteCarloOutputs: the result kept no runs or summaries");
  }
  MonteCarloWriter writer(dir);
  for (std::size_t k = 0; k < mc.runs.size(); ++k) writer.Add(int(k), mc.runs[k], mc.summaries[k]);
  writer.Finish(summary, mc);
}

nlohmann::json IsamMetrics(const IsamRunResult& r, const IsamRunParams& params) {
  nlohmann::json metrics = {
      {"known_association", params.ekf.known_association()},
      {"association", IsamParamsJson(params)["association"]},
      {"poses", r.estimate.size()},
      {"sightings", r.sightings},
      {"dropped", r.dropped},
      {"association_agreement", r.association_agreement},
      {"landmarks_mapped", r.map.landmarks.size()},
      {"odometry_covariance_scale", params.odometry_covariance_scale},
      {"sighting_covariance_scale", params.sighting_covariance_scale},
      {"wall_time_s", r.wall_time_s},
      {"filter_counters", CountersJson(r.counters)},
      {"params", IsamParamsJson(params)}};
  if (params.score_against_merged_reference) {
    metrics["association_agreement_merged"] = r.association_agreement_merged;
    metrics["reference_merges"] = r.reference_merges;
  }
  if (r.odometry_heading_drift) {
    metrics["odometry_heading_drift"] =
        HeadingDriftJson(*r.odometry_heading_drift, params.heading_drift_fit);
  }
  if (r.innovation_check) {
    metrics["innovation_check"] = InnovationCheckJson(*r.innovation_check);
    metrics["innovation_check"]["warning"] = IsamNoiseWarning(*r.innovation_check);
  }
  if (r.smoothed_reference) {
    const IsamReferenceErrors& e = *r.smoothed_reference;
    metrics["smoothed_reference"] = {{"ate_rmse_m", e.ate.rmse_m},
                                     {"ate_max_m", e.ate.max_m},
                                     {"map_rmse_m", e.map_rmse_m},
                                     {"landmarks_compared", e.landmarks_compared}};
  } else if (!r.smoothed_reference_failure.empty()) {
    metrics["smoothed_reference"] = {{"error", r.smoothed_reference_failure}};
  }
  return metrics;
}

void WriteIsamOutputs(const std::filesystem::path& dir, const nlohmann::json& metrics,
                      const IsamRunResult& result) {
  std::filesystem::create_directories(dir);
  WriteTumTrajectory(dir / "estimate.tum", result.estimate);
  WriteLandmarkMapCsv(dir / "map.csv", result.map);
  WritePoseCovarianceCsv(dir / "pose_covariance.csv", result.estimate, result.pose_covariance);
  WriteLandmarkMapHistoryCsv(dir / "map_history.csv", result.map_history);
  WriteJson(dir / "metrics.json", metrics);
}

}  // namespace slamkit
