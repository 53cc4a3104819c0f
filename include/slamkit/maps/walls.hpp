#pragma once

#include <utility>
#include <vector>

#include <Eigen/Core>

namespace slamkit {

// A wall from one end point to the other, in metres.
using WallSegment = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

// The walls of a floor plan (a building's outline, a maze, an occupancy image's edges).
using Walls = std::vector<WallSegment>;

}  // namespace slamkit
