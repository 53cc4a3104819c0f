#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "slamkit/io/param_table.hpp"
#include "slamkit/runners/cooperative/coop_run.hpp"
#include "slamkit/sim/fleet.hpp"

namespace slamkit {

// What a cooperative config file (configs/marine_eo.yaml, configs/mrclam.yaml) holds: the
// simulated fleet (when it simulates one), the filters and the Monte Carlo settings.
struct CoopConfig {
  FleetScenarioParams scenario;  // empty `vehicles` in a file for a recorded log
  RouteParams route;             // every vehicle's loops and switch distance
  CoopFilterParams filter;
  int runs = 1;
  std::uint64_t seed = 1;
};

// The file's scalar keys (io/param_table.hpp); `vehicles` is a Listed line LoadCoopConfig reads
// beside the table.
config::ParamTable CoopParamTable(CoopConfig& config);

// Loads a cooperative config (docs/cooperative.md lists the keys). Angles in degrees (`_deg`).
// Throws InputError naming the file, the key (with its line) and the reason.
CoopConfig LoadCoopConfig(const std::filesystem::path& path);

// The effective parameters, for metrics.json.
nlohmann::json CoopConfigJson(CoopConfig config);

}  // namespace slamkit
