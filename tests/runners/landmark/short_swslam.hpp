#pragma once

#include <filesystem>

#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {

// configs/swslam.yaml cut to the route's first leg past the first dense cluster and back: short
// enough for a test, and SWSLAM still detours there.
inline ScenarioConfig ShortSwslam() {
  ScenarioConfig c =
      LoadScenario(std::filesystem::path(SLAMKIT_SOURCE_DIR) / "configs" / "swslam.yaml");
  c.scenario.route.waypoints_m = {{8, 8}, {30, 3}, {52, 3}, {60, 20}};
  c.scenario.max_steps = 4000;
  return c;
}

}  // namespace slamkit
