#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/io/param_table.hpp"
#include "slamkit/planning/swslam_planner.hpp"
#include "slamkit/runners/landmark/fastslam_sampling.hpp"
#include "slamkit/sim/scenario.hpp"

namespace slamkit {

// Who picks the next waypoint in a closed-loop run (runners/active_run.hpp): the route alone, or
// SWSLAM's self-detected waypoints (SPEC S2).
enum class PlannerKind { kRoute, kSwslam };

struct PlannerConfig {
  PlannerKind kind = PlannerKind::kRoute;
  // The area-of-interest trigger and K-means. With kRoute the trigger still delimits the route
  // sections (no detours), so route and SWSLAM runs report comparable sections; `detour` is set
  // from `kind` by the runner.
  SwslamPlannerParams swslam;
};

// What a scenario file (configs/*.yaml) holds: the simulation and the filter run on it.
struct ScenarioConfig {
  ScenarioParams scenario;
  EkfSlamParams ekf;
  PlannerConfig planner;
  // How FastSLAM samples when a run uses it (FactoryForFilter; its other params follow ekf).
  FastSlamSampling fastslam;
};

// The scenario file's scalar keys (io/param_table.hpp), the lines pointing into `config`: the
// lists, the landmark file, the initial pose and `ekf.known_association` are Listed lines that
// LoadScenario reads beside the table.
config::ParamTable ScenarioParamTable(ScenarioConfig& config);
// metrics.json's `params` of a run on a scenario: every line of its table, and the association.
nlohmann::json ScenarioParamsJson(const ScenarioConfig& config);

// The `world` and `ekf` sections' lines, for the other simulated configs (the cooperative one).
void AddScenarioWorldLines(WorldSpec& w, config::ParamTable& t);
void AddScenarioEkfLines(EkfSlamParams& e, config::ParamTable& t);
// What the `world` section holds beside its lines (clusters, the landmark file, relative to
// `path`), with its checks; after ReadParams with a table holding AddScenarioWorldLines.
void ReadScenarioWorld(const YAML::Node& yaml, const std::filesystem::path& path,
                       const config::ParamTable& table, WorldSpec* world);

// Loads a scenario YAML file (configs/*.yaml; the keys are documented in docs/scenario.md).
// Every key names its unit; angles in configs are in degrees (`_deg`) and converted here.
// Throws InputError naming the file, the key (with its line) and the reason for an unknown key,
// a wrong type, or an out-of-range value. A `landmarks_csv` path is read relative to the file.
ScenarioConfig LoadScenario(const std::filesystem::path& path);

}  // namespace slamkit
