#pragma once

#include <memory>
#include <string>
#include <vector>

#include "slamkit/filters/graph/graph_grid_slam.hpp"
#include "slamkit/filters/grid/rbpf_grid_slam.hpp"
#include "slamkit/filters/grid_slam.hpp"

namespace slamkit {

// The grid SLAM back ends a config can name (its `backend` key).
enum class GridBackend {
  kRbpf,   // RbpfGridSlam
  kGraph,  // GraphGridSlam
};

// The names of the back ends, in GridBackend's order: what configs and metrics.json spell.
const std::vector<std::string>& GridBackendNames();

// Everything that makes a grid SLAM: which back end, and each back end's params. The laser and
// map settings both back ends share (usable range, ray insertion, the grid, the initial pose,
// the seed) are rbpf's; MakeGridSlam copies them into graph's.
struct GridSlamConfig {
  GridBackend backend = GridBackend::kRbpf;
  RbpfGridSlamParams rbpf;
  GraphGridSlamParams graph;
};

// config.graph with the shared laser, map and seed settings taken from config.rbpf.
GraphGridSlamParams EffectiveGraphParams(const GridSlamConfig& config);

// The filter `config` names. Throws std::invalid_argument for params the filter cannot take
// (a map's resolution or extent), before any scan is read.
std::unique_ptr<GridSlam> MakeGridSlam(const GridSlamConfig& config);

}  // namespace slamkit
