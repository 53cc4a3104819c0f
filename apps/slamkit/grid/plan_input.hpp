#pragma once

// For `gridsim` and `gridexplore`: the floor plan a --plan option names.

#include <string>

#include "slamkit/sim/floor_plan.hpp"

namespace slamkit::app {

// 'maze' (SPEC S4's 25 m square maze), a map_server map (a name ending .yaml or .yml), or a walls
// file (any other name: `x1 y1 x2 y2` walls and `poly ...` lines). Read errors are InputErrors
// naming the file and line.
FloorPlan ReadPlan(const std::string& plan);

}  // namespace slamkit::app
