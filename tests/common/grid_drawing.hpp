#pragma once

// Walls drawn into an occupancy grid for the grid-feature and structure-prediction tests.

#include <cmath>

#include <Eigen/Core>

#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit::testing {

// Adds `log_odds` once to every cell the segment a–b passes through (sampled every 1/20 cell):
// the segment's supercover, symmetric about it, as a wall seen by a laser would be.
inline void DrawWall(OccupancyGrid& grid, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     float log_odds = 3.0f) {
  const int n = static_cast<int>(std::ceil((b - a).norm() / (grid.resolution() / 20.0))) + 1;
  CellIndex last{0, 0};
  for (int i = 0; i <= n; ++i) {
    const CellIndex c = grid.WorldToCell(a + (b - a) * (double(i) / n));
    if (i > 0 && c == last) continue;
    grid.Update(c, log_odds);
    last = c;
  }
}

}  // namespace slamkit::testing
