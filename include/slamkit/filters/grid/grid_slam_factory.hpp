#pragma once

#include <memory>
#include <string>
#include <vector>

#include "slamkit/filters/grid/rbpf_grid_slam.hpp"
#include "slamkit/filters/grid_slam.hpp"

namespace slamkit {

// The grid SLAM back ends a config can name (its `backend` key).
enum class GridBackend {
  kRbpf,  // RbpfGridSlam
};

// The names of the back ends, in GridBackend's order: what configs and metrics.json spell.
const std::vector<std::string>& GridBackendNames();

// Everything that makes a grid SLAM: which back end, and each back end's params.
struct GridSlamConfig {
  GridBackend backend = GridBackend::kRbpf;
  RbpfGridSlamParams rbpf;
};

// The filter `config` names. Throws std::invalid_argument for params the filter cannot take
// (a map's resolution or extent), before any scan is read.
std::unique_ptr<GridSlam> MakeGridSlam(const GridSlamConfig& config);

}  // namespace slamkit
