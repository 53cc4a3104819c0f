#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "slamkit/runners/landmark/study.hpp"

namespace slamkit {

// study.json: `scenario`, `runs`, `seed`, `particles`, `sections_note` (how the route methods'
// sections are chosen) and `methods`, one per method in the seed's order: `key`, `title`,
// `filter`, `planner`, `wall_time_s`, `anees`, `anees_band`, `anees_fraction_in_band`,
// `anees_run_median` (the median over runs of each run's mean NEES),
// `position_rmse_m`, `heading_rmse_rad` (RMS over runs), `position_rms_m` and `heading_rms_rad`
// (`mean` and `variance` over runs of each run's RMS: Tables 4-5), `landmarks_mapped`,
// `map_rmse_m`, `association`, `steps` (the longest run's), `sections` (Tables 1-3, as
// metrics.json's), `paper` (the seed's figures for that method) and `per_run`.
nlohmann::json StudyJson(const ScenarioConfig& config, const StudyResult& result);

// tables.md: seed 001's Tables 1-5 with our figures beside the paper's, and the consistency
// summary (ANEES, band, share of steps in it) and wall time of each method.
std::string StudyTablesMarkdown(const StudyResult& result);

// Writes DIR/table1.csv … table3.csv (sections 1-3), table4.csv (position error),
// table5.csv (heading error), sections.csv (every section of every method), nees.csv (each
// method's ANEES and runs per step), tables.md, study.json and, last, metrics.json (study.json
// without the per_run lists: its presence means the study completed), each atomically.
void WriteStudyOutputs(const std::filesystem::path& dir, const ScenarioConfig& config,
                       const StudyResult& result);

}  // namespace slamkit
