#pragma once

#include <vector>

#include "slamkit/core/pose2.hpp"
#include "slamkit/sim/controller.hpp"
#include "slamkit/sim/floor_plan.hpp"

namespace slamkit {

// The centre lines of a square maze's corridors along one axis (the same for x and y), lowest
// first: the outer ring's two, and one between each pair of neighbouring blocks. Empty when the
// maze has no block.
std::vector<double> SquareMazeCorridorCentres(const SquareMazeParams& params = {});

// A closed route along the centre line of every corridor of MakeSquareMaze(params), so that a
// robot driving it sees the whole maze: from the lower-left corner of the outer ring, east and west
// along every row of corridors in turn (a serpentine), then north and south along every column,
// and back to the start along the outer ring. Waypoints are the turning points only, each on a
// crossing of two centre lines, so every leg follows a corridor's centre line (half a corridor
// width from the walls). `loops` and `switch_distance_m` as RouteParams. The default switch
// distance suits a turn radius (speed / ControllerParams::max_turn_rate_radps) of 0.5 m: the
// robot starts turning 0.25 m before a crossing and ends the turn 0.25 m past the centre line,
// which keeps it about 0.5 m off the block corners in 2.2 m corridors; a larger turn radius
// cuts the corners closer. Throws std::invalid_argument for a maze without blocks.
RouteParams MazeRoute(const SquareMazeParams& params = {}, int loops = 1,
                      double switch_distance_m = 0.25);

// Where a robot starts a route: at its first waypoint, facing the second.
Pose2 RouteStartPose(const RouteParams& route);

}  // namespace slamkit
