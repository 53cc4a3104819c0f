#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "slamkit/filters/grid_slam_factory.hpp"
#include "slamkit/io/param_table.hpp"

namespace slamkit {

// The parameters of a grid SLAM's config, pointing into `config`: what LoadGridConfig reads,
// GridParamsJson writes and `slamkit grid`'s filter options set (the lines with a flag).
config::ParamTable GridParamTable(GridSlamConfig& config);

// Reads a grid SLAM's config from a YAML file: `backend` (rbpf, the default, the only one so
// far) and that back end's parameters at the top level (configs/grid.yaml lists every key with
// its unit and default; keys left out keep `defaults`). Throws InputError naming the file, line
// and key for an unknown key, a wrong type, a value out of range or an unknown choice.
GridSlamConfig LoadGridConfig(const std::filesystem::path& path,
                              const GridSlamConfig& defaults = {});

// Every parameter LoadGridConfig reads, with the same keys: the effective parameters of a run, so
// that its metrics.json can reproduce it (written back as YAML, it loads to the same values).
nlohmann::json GridParamsJson(const GridSlamConfig& config);

}  // namespace slamkit
