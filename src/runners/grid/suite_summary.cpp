#include "slamkit/runners/grid/suite_summary.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <string>

#include <fmt/format.h>

#include "slamkit/eval/spread.hpp"
#include "slamkit/io/atomic_file.hpp"
#include "slamkit/io/writers.hpp"

namespace slamkit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// `key` of a run's metrics as a number, NaN when absent (a run without that reference).
double Value(const SuiteRunRecord& r, const std::string& key) {
  if (key == "wall_time_s") return r.wall_time_s;
  if (key == "peak_rss_mib") return r.peak_rss_mib;
  if (!r.metrics.is_object()) return kNaN;
  const auto it = r.metrics.find(key);
  return it != r.metrics.end() && it->is_number() ? it->get<double>() : kNaN;
}

std::string Cell(double v, const char* format = "{:.4f}") {
  return std::isfinite(v) ? fmt::format(fmt::runtime(format), v) : "";
}

// `key` over the runs that have it (a log without a reference has no ATE).
Spread RunSpreadOf(const std::vector<const SuiteRunRecord*>& runs, const std::string& key) {
  std::vector<double> values;
  for (const SuiteRunRecord* r : runs) {
    const double v = Value(*r, key);
    if (std::isfinite(v)) values.push_back(v);
  }
  return SpreadOf(values);
}

std::string SpreadCell(const Spread& s) {
  if (s.count == 0) return "";
  if (s.count == 1) return fmt::format("{:.4f}", s.mean);
  return fmt::format("{:.4f} ({:.4f}–{:.4f})", s.mean, s.min, s.max);
}

// The run's log, with its back end when it is not the particle filter: a suite of both back ends
// summarises each apart.
std::string LogLabel(const SuiteRunRecord& r) {
  return r.backend == "rbpf" ? r.log : r.log + " (" + r.backend + ")";
}

// The completed runs of each log and back end, in manifest order.
std::vector<std::pair<std::string, std::vector<const SuiteRunRecord*>>> ByLog(
    const std::vector<SuiteRunRecord>& runs, std::vector<int>* failed) {
  std::vector<std::pair<std::string, std::vector<const SuiteRunRecord*>>> logs;
  for (const SuiteRunRecord& r : runs) {
    const std::string label = LogLabel(r);
    auto it = std::find_if(logs.begin(), logs.end(),
                           [&](const auto& l) { return l.first == label; });
    if (it == logs.end()) {
      logs.push_back({label, {}});
      failed->push_back(0);
      it = std::prev(logs.end());
    }
    if (r.failure.empty()) {
      it->second.push_back(&r);
    } else {
      ++(*failed)[static_cast<std::size_t>(it - logs.begin())];
    }
  }
  return logs;
}

std::string Status(const SuiteRunRecord& r) { return r.failure.empty() ? "ok" : "failed"; }

}  // namespace

const std::vector<std::string>& SuiteSummaryColumns() {
  static const std::vector<std::string> columns = {
      "scans", "ate_rmse_m", "ate_mean_m", "ate_max_m", "rpe_trans_mean_m", "rpe_rot_mean_deg",
      "relations_trans_mean_m", "relations_rot_mean_deg", "odometry_ate_rmse_m",
      "odometry_relations_trans_mean_m", "wall_time_s", "scans_per_s", "peak_rss_mib",
      "resamples"};
  return columns;
}

nlohmann::json SuiteSummaryJson(const std::vector<SuiteRunRecord>& runs) {
  nlohmann::json out = {{"runs", nlohmann::json::array()}, {"logs", nlohmann::json::array()}};
  for (const SuiteRunRecord& r : runs) {
    out["runs"].push_back({{"log", r.log}, {"backend", r.backend}, {"seed", r.seed},
                           {"status", Status(r)},
                           {"exit_code", r.exit_code}, {"failure", r.failure},
                           {"wall_time_s", r.wall_time_s}, {"peak_rss_mib", r.peak_rss_mib},
                           {"metrics", r.metrics}});
  }
  std::vector<int> failed;
  const auto logs = ByLog(runs, &failed);
  for (std::size_t i = 0; i < logs.size(); ++i) {
    nlohmann::json log = {{"log", logs[i].first}, {"completed", logs[i].second.size()},
                          {"failed", failed[i]}};
    if (!logs[i].second.empty()) {
      log["log"] = logs[i].second.front()->log;
      log["backend"] = logs[i].second.front()->backend;
    }
    for (const char* key : {"ate_rmse_m", "relations_trans_mean_m", "odometry_ate_rmse_m",
                            "odometry_relations_trans_mean_m", "wall_time_s", "peak_rss_mib"}) {
      const Spread s = RunSpreadOf(logs[i].second, key);
      if (s.count > 0) log[key] = {{"mean", s.mean}, {"min", s.min}, {"max", s.max}};
    }
    out["logs"].push_back(log);
  }
  return out;
}

namespace {

std::string SummaryCsv(const std::vector<SuiteRunRecord>& runs) {
  std::string csv = "log,seed,status";
  for (const std::string& c : SuiteSummaryColumns()) {
    csv += ',';
    csv += c;
  }
  csv += "\n";
  for (const SuiteRunRecord& r : runs) {
    csv += fmt::format("{},{},{}", LogLabel(r), r.seed, Status(r));
    for (const std::string& c : SuiteSummaryColumns()) {
      csv += ',';
      csv += Cell(Value(r, c), "{:.6g}");
    }
    csv += "\n";
  }
  return csv;
}

std::string PerLogTable(const std::vector<SuiteRunRecord>& runs) {
  std::string md =
      "| log | runs | ATE RMSE [m] mean (min–max) | odometry ATE [m] | relations [m] mean "
      "(min–max) | odometry relations [m] | wall [s] | peak [MiB] |\n"
      "|---|---|---|---|---|---|---|---|\n";
  std::vector<int> failed;
  const auto logs = ByLog(runs, &failed);
  for (std::size_t i = 0; i < logs.size(); ++i) {
    const auto& [name, done] = logs[i];
    md += fmt::format("| {} | {}{} | {} | {} | {} | {} | {} | {} |\n", name, done.size(),
                      failed[i] > 0 ? fmt::format(" ({} failed)", failed[i]) : "",
                      SpreadCell(RunSpreadOf(done, "ate_rmse_m")),
                      Cell(RunSpreadOf(done, "odometry_ate_rmse_m").mean),
                      SpreadCell(RunSpreadOf(done, "relations_trans_mean_m")),
                      Cell(RunSpreadOf(done, "odometry_relations_trans_mean_m").mean),
                      Cell(RunSpreadOf(done, "wall_time_s").mean, "{:.1f}"),
                      Cell(RunSpreadOf(done, "peak_rss_mib").max, "{:.0f}"));
  }
  return md;
}

std::string PerRunTable(const std::vector<SuiteRunRecord>& runs) {
  std::string md =
      "| log | seed | status | scans | ATE RMSE [m] | ATE max [m] | RPE [m] | RPE [deg] | "
      "relations [m] | relations [deg] | wall [s] | scans/s | peak [MiB] | resamples |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SuiteRunRecord& r : runs) {
    md += fmt::format("| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                      LogLabel(r), r.backend == "rbpf" ? fmt::format("{}", r.seed) : "–",
                      r.failure.empty() ? "ok" : "failed: " + r.failure,
                      Cell(Value(r, "scans"), "{:.0f}"), Cell(Value(r, "ate_rmse_m")),
                      Cell(Value(r, "ate_max_m")), Cell(Value(r, "rpe_trans_mean_m")),
                      Cell(Value(r, "rpe_rot_mean_deg"), "{:.3f}"),
                      Cell(Value(r, "relations_trans_mean_m")),
                      Cell(Value(r, "relations_rot_mean_deg"), "{:.3f}"),
                      Cell(r.wall_time_s, "{:.1f}"), Cell(Value(r, "scans_per_s"), "{:.0f}"),
                      Cell(r.peak_rss_mib, "{:.0f}"), Cell(Value(r, "resamples"), "{:.0f}"));
  }
  return md;
}

}  // namespace

void WriteSuiteSummary(const std::filesystem::path& dir, const std::string& title,
                       const std::vector<SuiteRunRecord>& runs, const nlohmann::json& shard) {
  WriteFileAtomically(dir / "summary.csv", SummaryCsv(runs));
  nlohmann::json summary = SuiteSummaryJson(runs);
  if (!shard.is_null()) summary["shard"] = shard;
  WriteJson(dir / "summary.json", summary);
  const std::string md = fmt::format(
      "# {}\n\nATE after rigid alignment against each log's reference; relations as Kümmerle et "
      "al. 2009. Odometry: the log's raw odometry scored the same way.\n\n## Per log\n\n{}\n"
      "## Per run\n\n{}",
      title, PerLogTable(runs), PerRunTable(runs));
  WriteFileAtomically(dir / "summary.md", md);
}

}  // namespace slamkit
