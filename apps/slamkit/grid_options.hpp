#pragma once

#include <CLI/CLI.hpp>

#include "slamkit/filters/rbpf_grid_slam.hpp"

namespace slamkit::app {

// The RbpfGridSlam options shared by `grid` and `gridsim`.
void AddGridFilterOptions(CLI::App* cmd, RbpfGridSlamParams& params);

// Call once the options are parsed: one --usable-range for every use of the laser.
void FinishGridFilterOptions(RbpfGridSlamParams& params);

}  // namespace slamkit::app
