#pragma once

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "slamkit/runners/landmark/isam_run.hpp"
#include "slamkit/runners/landmark/monte_carlo.hpp"

namespace slamkit {

// metrics.json's summary keys of a Monte Carlo experiment (the output contract in README.md);
// MonteCarloWriter::Finish adds `per_run`. Timing keys (`step_time_*`) are the only ones that
// vary between two runs with the same seed.
nlohmann::json MonteCarloMetrics(const ScenarioConfig& config, const MonteCarloParams& params,
                                  const MonteCarloResult& result);

// The keys of MonteCarloMetrics that come from the result alone: `steps` onwards.
nlohmann::json MonteCarloResultJson(const MonteCarloResult& result);

// Run k's entry of metrics.json's `per_run`: the summary keys, per run, with `run`: k.
nlohmann::json RunSummaryJson(int k, const RunSummary& summary);

// Writes a Monte Carlo experiment into a fresh folder DIR as its runs finish, keeping none of
// them in memory. Add(k, ...) writes DIR/run_<k>/{estimate.tum, truth.tum, map.csv, errors.csv}
// and appends run k's per_run entry to a scratch file in DIR; Finish writes DIR/world.csv,
// DIR/consistency.csv (t, ANEES, RMSEs and runs per step) and, last, DIR/metrics.json: the summary
// keys, then `per_run` copied from the scratch file, which is removed. Each file is written
// atomically. Throws std::runtime_error naming the file when a write fails.
class MonteCarloWriter {
 public:
  explicit MonteCarloWriter(std::filesystem::path dir);
  ~MonteCarloWriter();
  MonteCarloWriter(const MonteCarloWriter&) = delete;
  MonteCarloWriter& operator=(const MonteCarloWriter&) = delete;

  void Add(int k, const RunResult& run, const RunSummary& summary);
  // The same, with `extra`'s keys added to run k's per_run entry (a closed loop's sections).
  void Add(int k, const RunResult& run, const RunSummary& summary, const nlohmann::json& extra);
  // Only the per_run entry of a run whose folder the caller provides (slamkit merge).
  void AddEntry(const nlohmann::json& entry);
  void Finish(const nlohmann::json& summary, const MonteCarloResult& result);

 private:
  std::filesystem::path dir_;
  std::filesystem::path scratch_path_;
  std::ofstream scratch_;
  int runs_ = 0;
};

// MonteCarloWriter over a result that kept its runs and summaries (MonteCarloParams::keep_runs,
// keep_summaries): the same folder in one call.
void WriteMonteCarloOutputs(const std::filesystem::path& dir, const nlohmann::json& summary,
                            const MonteCarloResult& result);

// metrics.json of an iSAM-log run: association_agreement, landmarks_mapped, wall_time_s, ...
// The warning for a run whose innovations sit far outside their band, naming the likely cause
// and the keys that address it; empty when the check found nothing to say.
std::string IsamNoiseWarning(const InnovationCheck& check);
nlohmann::json IsamMetrics(const IsamRunResult& result, const IsamRunParams& params);

// Writes DIR/metrics.json, DIR/estimate.tum and DIR/map.csv.
void WriteIsamOutputs(const std::filesystem::path& dir, const nlohmann::json& metrics,
                      const IsamRunResult& result);

}  // namespace slamkit
