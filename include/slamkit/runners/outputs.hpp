#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "slamkit/runners/isam_run.hpp"
#include "slamkit/runners/monte_carlo.hpp"

namespace slamkit {

// metrics.json of a Monte Carlo experiment (the output contract in README.md): summary keys,
// then the same per run under `per_run`. Timing keys (`step_time_*`) are the only ones that vary
// between two runs with the same seed.
nlohmann::json MonteCarloMetrics(const ScenarioConfig& config, const MonteCarloParams& params,
                                  const MonteCarloResult& result);

// Writes DIR/run_<k>/{estimate.tum, truth.tum, map.csv, errors.csv}, each file atomically: the
// per-run outputs, written as each run finishes (MonteCarloParams::on_run) so that no run has to
// be kept.
void WriteMonteCarloRun(const std::filesystem::path& dir, int k, const RunResult& run);

// Writes DIR/metrics.json, DIR/world.csv, DIR/consistency.csv (t, ANEES, RMSEs per step) and,
// for the runs `result` kept (MonteCarloParams::keep_runs), DIR/run_<k>/ as WriteMonteCarloRun;
// each file atomically, metrics.json last.
void WriteMonteCarloOutputs(const std::filesystem::path& dir, const nlohmann::json& metrics,
                            const MonteCarloResult& result);

// metrics.json of an iSAM-log run: association_agreement, landmarks_mapped, wall_time_s, ...
nlohmann::json IsamMetrics(const IsamRunResult& result, const IsamRunParams& params);

// Writes DIR/metrics.json, DIR/estimate.tum and DIR/map.csv.
void WriteIsamOutputs(const std::filesystem::path& dir, const nlohmann::json& metrics,
                      const IsamRunResult& result);

}  // namespace slamkit
