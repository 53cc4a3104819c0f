#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "slamkit/filters/grid/rbpf_grid_slam.hpp"

namespace slamkit {

// Reads the grid filter's parameters from a YAML file (configs/grid.yaml lists every key with its
// unit and default; keys left out keep `defaults`). Throws InputError naming the file, line and
// key for an unknown key, a wrong type, a value out of range or an unknown choice.
RbpfGridSlamParams LoadGridConfig(const std::filesystem::path& path,
                                  const RbpfGridSlamParams& defaults = {});

// Every parameter LoadGridConfig reads, with the same keys: the effective parameters of a run, so
// that its metrics.json can reproduce it (written back as YAML, it loads to the same values).
nlohmann::json GridParamsJson(const RbpfGridSlamParams& params);

}  // namespace slamkit
