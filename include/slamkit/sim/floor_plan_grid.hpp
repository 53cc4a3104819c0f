#pragma once

#include <Eigen/Core>

#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/sim/floor_plan.hpp"

namespace slamkit {

// The true occupancy map of a floor plan on a grid (SPEC S4: what an explored and a predicted map
// are scored against): every cell a wall passes through is occupied (at full log-odds), every cell
// reachable from `inside_m` without crossing one (4-connected, within the walls' bounding box) is
// free, every other cell unknown. Throws std::invalid_argument when `inside_m` lies on a wall or
// outside the walls' bounding box.
OccupancyGrid FloorPlanOccupancy(const FloorPlan& plan, const OccupancyGridParams& grid,
                                 const Eigen::Vector2d& inside_m);

}  // namespace slamkit
