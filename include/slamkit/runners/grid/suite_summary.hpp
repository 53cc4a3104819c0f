#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace slamkit {

// One grid run of a suite (one log, one seed) as its driver saw it.
struct SuiteRunRecord {
  std::string log;             // the manifest's name
  std::string backend = "rbpf";  // the grid back end (GridBackendNames)
  std::uint64_t seed = 0;
  int exit_code = 0;           // of the run; 0 with a metrics.json is a completed run
  std::string failure;         // why it failed ("" when it completed)
  double wall_time_s = 0.0;    // as the driver measured it (start-up and evaluation included)
  double peak_rss_mib = 0.0;   // the run's own peak resident memory
  nlohmann::json metrics;      // the run's metrics.json; null when it wrote none
};

// The columns of summary.csv, in order: what a suite compares across logs and seeds.
const std::vector<std::string>& SuiteSummaryColumns();

// summary.json: every run's record with its metrics, and per log and back end the mean, min and
// max over its completed seeds of ATE RMSE and of the relations' translation error (where
// present). The tables name each run's back end when the runs have more than the particle
// filter's.
nlohmann::json SuiteSummaryJson(const std::vector<SuiteRunRecord>& runs);

// Writes DIR/summary.csv (one row per run), DIR/summary.json and DIR/summary.md (a table per run
// and one per log, odometry beside the estimate), each atomically.
// A shard's output (`--shard K/N`) gives `shard`, written to summary.json as its "shard" key.
void WriteSuiteSummary(const std::filesystem::path& dir, const std::string& title,
                       const std::vector<SuiteRunRecord>& runs,
                       const nlohmann::json& shard = nullptr);

}  // namespace slamkit
