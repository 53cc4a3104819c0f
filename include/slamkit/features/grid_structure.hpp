#pragma once

#include <array>
#include <numbers>
#include <vector>

#include <Eigen/Core>

#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

// Line and corner features of a built occupancy-grid map (SPEC S4, step 3). The defaults suit the
// 0.1 m grid of SPEC S4 (the metric tolerances are about one cell there).
struct GridStructureParams {
  // Cells with a larger occupancy probability vote (map_server's occupied threshold).
  double occupied_probability = 0.65;
  // Hough θ resolution (rounded so that a whole number of steps covers [0, π)); the ρ resolution
  // is one cell.
  double angle_step_rad = std::numbers::pi / 180.0;
  // Shorter runs (end cell to end cell) are not walls. A Hough peak needs at least the cells a
  // digital line of this length has at 45° (length / (√2 · resolution)).
  double min_segment_length_m = 1.0;
  // Cells along one Hough line split into separate segments where consecutive cells are farther
  // apart (along the line) than this: a doorway.
  double max_gap_m = 0.3;
  // How far from a line a cell's centre may lie and still belong to it. The centres of a digital
  // line lie within 0.71 cells of it, and a perpendicular wall's cells start one full cell away:
  // 0.8 cells at 0.1 m.
  double line_tolerance_m = 0.08;
  // Budget: at most this many segments, strongest Hough peak first.
  int max_lines = 64;
  // Two lines meeting at less than this (as undirected lines, in [0, π/2]) are not a corner.
  double min_corner_angle_rad = std::numbers::pi / 6.0;
  // Each segment's nearer end must be this close to the two lines' intersection.
  double corner_max_gap_m = 0.4;
};

// A wall segment of the grid, in the world frame.
struct GridLine {
  // The segment's end cells' centres, projected onto the line fitted (total least squares) to its
  // cells, so that start→end is exactly the line's direction.
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d end_m = Eigen::Vector2d::Zero();
  // Direction of start→end, in (−π/2, π/2] ⊂ (−π, π]: start is the end of lower x (of lower y
  // for a vertical line), so the same wall always comes out the same way round.
  double angle_rad = 0.0;
  int cells = 0;  // occupied cells on it (a corner's cell counts for both of its walls)

  double LengthM() const { return (end_m - start_m).norm(); }
};

// A corner: where two segments end at (near) one point, a control point of SPEC S4 step 3.
// line_angles_rad are the directions of its two arms pointing AWAY from the corner along each
// segment (toward the segment's far end), in (−π, π], in the order of the lines they come from.
struct GridCorner {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  // the two lines' intersection
  std::array<double, 2> line_angles_rad = {0.0, 0.0};
};

// SPEC S4, step 3 (lines by Hough transform): segments among the grid's occupied cells whose
// centres lie within radius_m of center_m (cells outside the disc are neither read nor voted: a
// prediction never scans the whole map), strongest first. Deterministic. Throws
// std::invalid_argument for a non-positive angle step, tolerance or segment length.
std::vector<GridLine> ExtractGridLines(const OccupancyGrid& grid, const Eigen::Vector2d& center_m,
                                       double radius_m, const GridStructureParams& params = {});

// SPEC S4, step 3 (corners at line intersections): L-corners, where each of two segments has an
// end within corner_max_gap_m of their lines' intersection. T-junctions (the intersection inside
// one segment) are not corners here. Corners closer than corner_max_gap_m to an earlier one (of
// stronger lines) are dropped.
std::vector<GridCorner> ExtractGridCorners(const std::vector<GridLine>& lines,
                                           const GridStructureParams& params = {});

}  // namespace slamkit
