#pragma once

#include <filesystem>

#include "slamkit/filters/ekf_slam.hpp"
#include "slamkit/sim/scenario.hpp"

namespace slamkit {

// What a scenario file (configs/*.yaml) holds: the simulation and the filter run on it.
struct ScenarioConfig {
  ScenarioParams scenario;
  EkfSlamParams ekf;
};

// Loads a scenario YAML file (configs/*.yaml; the keys are documented in docs/scenario.md).
// Every key names its unit; angles in configs are in degrees (`_deg`) and converted here.
// Throws InputError naming the file, the key (with its line) and the reason for an unknown key,
// a wrong type, or an out-of-range value. A `landmarks_csv` path is read relative to the file.
ScenarioConfig LoadScenario(const std::filesystem::path& path);

}  // namespace slamkit
