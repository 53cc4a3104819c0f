// The grids and brute-force references the path planner's tests share: rooms drawn cell by
// cell, octile distances, clearances and step costs as GridPathParams documents them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>

#include "slamkit/planning/grid_paths.hpp"

namespace slamkit::grid_paths_test {

inline constexpr double kRes = 0.1;
inline constexpr double kInf = std::numeric_limits<double>::infinity();

// Cells x0..x1 × y0..y1 made '#' occupied, '.' free or ' ' unknown.
inline void Fill(OccupancyGrid& grid, int x0, int y0, int x1, int y1, char kind) {
  const float target = kind == '#' ? 3.0f : kind == '.' ? -3.0f : 0.0f;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) grid.Update({x, y}, target - grid.LogOdds({x, y}));
  }
}

template <class F>
inline void ForEachCell(int w, int h, const F& f) {  // cells 0..w-1 × 0..h-1
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) f(CellIndex{x, y});
  }
}

// Free cells 1..w-2 × 1..h-2 inside a one-cell wall.
inline OccupancyGrid Room(int w, int h) {
  OccupancyGrid grid(OccupancyGridParams{kRes});
  Fill(grid, 0, 0, w - 1, h - 1, '#');
  Fill(grid, 1, 1, w - 2, h - 2, '.');
  return grid;
}

inline Eigen::Vector2d Centre(const CellIndex& c) {
  return {(c.x + 0.5) * kRes, (c.y + 0.5) * kRes};
}

inline double Octile(const CellIndex& a, const CellIndex& b) {
  const int dx = std::abs(a.x - b.x), dy = std::abs(a.y - b.y);
  return kRes * (std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy));
}

// The distance from a cell's centre to the nearest point of an occupied square, by brute force.
inline double ExactClearance(const OccupancyGrid& grid, const CellIndex& c) {
  double best = kInf;
  for (int y = grid.min_cell().y; y <= grid.max_cell().y; ++y) {
    for (int x = grid.min_cell().x; x <= grid.max_cell().x; ++x) {
      if (!(grid.Probability({x, y}) > 0.65)) continue;
      const double ex = std::max(std::abs(x - c.x) - 0.5, 0.0);
      const double ey = std::max(std::abs(y - c.y) - 0.5, 0.0);
      best = std::min(best, kRes * std::hypot(ex, ey));
    }
  }
  return best;
}

// The per-metre penalty as GridPathParams documents it.
inline double Penalty(double clearance, const GridPathParams& p) {
  if (clearance < p.robot_radius_m) return p.clearance_cost_weight;
  if (clearance >= p.robot_radius_m + p.clearance_m) return 0.0;
  return p.clearance_cost_weight * (1.0 - (clearance - p.robot_radius_m) / p.clearance_m);
}

inline double StepCost(const GridPathCosts& costs, const CellIndex& a, const CellIndex& b) {
  const double length = (a.x != b.x && a.y != b.y) ? kRes * std::sqrt(2.0) : kRes;
  return length * (1.0 + 0.5 * (Penalty(costs.Clearance(a), costs.params()) +
                                Penalty(costs.Clearance(b), costs.params())));
}

}  // namespace slamkit::grid_paths_test
