#pragma once

#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/filters/grid/scan_matcher.hpp"
#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

// P-SLAM's predicted structure h (SPEC S4, step 4; seed 004, Section III-C): the cells of an
// aligned reference region that fall on cells unexplored in the map it was predicted from, with
// the reference cells' log-odds. It lives in the frame of that map (the best particle's when the
// prediction was asked for); each particle sees it re-posed into its own frame.
struct GridHypothesis {
  int id = 0;
  double t_s = 0.0;                                          // the request's scan time
  Eigen::Vector2d target_m = Eigen::Vector2d::Zero();        // the target frontier cell f
  Eigen::Vector2d control_point_m = Eigen::Vector2d::Zero(); // the corner nearest f
  Eigen::Vector2d reference_point_m = Eigen::Vector2d::Zero();  // the matched corner
  double rotation_rad = 0.0;  // Γ's θ (seed Eq. 2): reference → target
  double similarity = 0.0;    // Ψ (Eq. 5) of the explored surroundings and the aligned reference
  int alignments = 0;         // Γ's evaluated
  OccupancyGrid cells;        // the predicted cells; every other cell 0 (unknown)
  int predicted_cells = 0;
  int occupied_cells = 0;
  double area_m2() const { return predicted_cells * cells.resolution() * cells.resolution(); }
};

// The hypothesis cells of `h` moved by `transform` (a point p of h's frame goes to
// transform ⊕ p), written into `layer` where it is still 0; cells `layer` already holds win.
// Sampled backwards (each cell of the moved bounding box reads h at transform⁻¹ of its centre),
// so a rotation leaves no holes. Both grids must share the resolution.
void AddMovedHypothesis(const OccupancyGrid& h, const Pose2& transform, OccupancyGrid& layer);

// How the beams of one scan bear on one hypothesis (seed Eq. 23), for the particle at `pose`
// with its own map `map`: z_u are the beams whose end falls on a cell unknown in `map` that `h`
// predicts (h seen through `to_particle`, as AddMovedHypothesis moves it), and a hit is such a
// beam with an occupied cell of h within `window_cells` of its end.
struct HypothesisSupport {
  int beams = 0;  // |z_u|
  int hits = 0;   // |h ∩ z_u|
  double HitRatio() const { return beams == 0 ? 0.0 : double(hits) / beams; }
};
HypothesisSupport MeasureSupport(const OccupancyGrid& h, const Pose2& to_particle,
                                 const OccupancyGrid& map, const ScanPoints& points,
                                 const Pose2& pose, int window_cells = 1);

// Seed Section IV, V(·): the cells of `h` (seen through `to_map`) that `map` has explored since;
// returns how many of h's cells are still unknown there.
int UnexploredCells(const OccupancyGrid& h, const Pose2& to_map, const OccupancyGrid& map);

// Calls visit(cell, steps) for every nonzero cell of `grid`, row by row.
template <class Visit>
void ForEachKnownCell(const OccupancyGrid& grid, const Visit& visit) {
  const CellIndex lo = grid.min_cell(), hi = grid.max_cell();
  for (int y = lo.y; y <= hi.y; ++y) {
    for (int x = lo.x; x <= hi.x; ++x) {
      const OccupancyGrid::CellValue v = grid.LogOddsSteps({x, y});
      if (v != 0) visit(CellIndex{x, y}, v);
    }
  }
}

}  // namespace slamkit
