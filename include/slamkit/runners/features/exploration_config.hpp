#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "slamkit/core/pose2.hpp"
#include "slamkit/io/param_table.hpp"
#include "slamkit/runners/features/exploration.hpp"
#include "slamkit/runners/features/feature_exploration.hpp"

namespace slamkit {

// One exploration experiment of SPEC S1 (configs/office_selection.yaml lists every key with its
// unit and default): the world, where the robot starts, the loop and the feature EKF.
struct ExplorationConfig {
  std::filesystem::path world;  // a floor-plan file; relative to the config file's folder
  Pose2 start;
  std::uint64_t seed = 1;
  ExplorationParams run;
  FeatureSlamParams slam;  // its odometry noise is set from run's
};

// The scalar parameters' table (io/param_table.hpp), its lines pointing into `config`; `world`
// and `start` are Listed lines, read beside it.
config::ParamTable ExplorationParamTable(ExplorationConfig& config);

// Reads `path`. Throws InputError naming the file, line and key for an unknown key, a wrong type,
// a value out of range or an unknown choice, and for a missing `world`.
ExplorationConfig LoadExplorationConfig(const std::filesystem::path& path);

// The effective parameters, with the keys LoadExplorationConfig reads, for metrics.json.
nlohmann::json ExplorationConfigJson(const ExplorationConfig& config);

}  // namespace slamkit
