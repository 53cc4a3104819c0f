// Ray casting (Bresenham) and the inverse sensor model that writes a laser scan into an
// OccupancyGrid (Thrun, Burgard & Fox, Probabilistic Robotics, ch. 9, in the
// simplified form of GMapping: free along the beam, occupied at its end).

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {
namespace {

// Calls visit(CellIndex) for the cells of the digital line from `from` to `to`, in order, with
// `to` itself only when `include_end`. Integer Bresenham: along the major axis (the one with the
// larger |delta|) every cell is visited once and the minor coordinate is the true line's, rounded
// to the nearest integer. A tie (the line passes exactly half-way between two cells) goes to the
// smaller minor coordinate in world terms, whichever end the ray starts from, so that a reversed
// ray visits exactly the same cells.
template <typename Visit>
void ForEachRayCell(const CellIndex& from, const CellIndex& to, bool include_end, Visit&& visit) {
  const int dx = to.x - from.x;
  const int dy = to.y - from.y;
  const bool x_major = std::abs(dx) >= std::abs(dy);
  const int major_len = x_major ? std::abs(dx) : std::abs(dy);
  const int minor_len = x_major ? std::abs(dy) : std::abs(dx);
  const int major_step = (x_major ? dx : dy) < 0 ? -1 : 1;
  const int minor_step = (x_major ? dy : dx) < 0 ? -1 : 1;
  // On a tie, stepping moves the minor coordinate down in world terms only when minor_step < 0.
  const bool step_on_tie = minor_step < 0;
  int major = x_major ? from.x : from.y;
  int minor = x_major ? from.y : from.x;
  // err = 2 · (k · minor_len - m · major_len) after k major steps and m minor steps, the signed
  // distance (scaled by 2 · major_len) of the true line from the current minor coordinate.
  long long err = 0;
  const int n = include_end ? major_len + 1 : major_len;
  for (int k = 0; k < n; ++k) {
    visit(x_major ? CellIndex{major, minor} : CellIndex{minor, major});
    major += major_step;
    err += 2LL * minor_len;
    if (err > major_len || (step_on_tie && err == major_len)) {
      minor += minor_step;
      err -= 2LL * major_len;
    }
  }
}

// The cells from `origin` up to (not including) `end` get `miss`.
void TraceMisses(OccupancyGrid& grid, const CellIndex& origin, const CellIndex& end, long miss) {
  grid.UpdateStepsAlong(
      [&](const auto& write) { ForEachRayCell(origin, end, /*include_end=*/false, write); },
      miss);
}

}  // namespace

std::vector<CellIndex> RayCells(const CellIndex& from, const CellIndex& to) {
  std::vector<CellIndex> cells;
  cells.reserve(static_cast<std::size_t>(std::max(std::abs(to.x - from.x),
                                                  std::abs(to.y - from.y))) + 1);
  ForEachRayCell(from, to, /*include_end=*/true, [&cells](const CellIndex& c) {
    cells.push_back(c);
  });
  return cells;
}

// Every beam with a finite positive range is cut to the usable range and traced from the laser's
// cell to its end cell: the cells before the end cell get log_odds_miss; the end cell gets
// log_odds_hit only for a return within the usable range, and nothing otherwise (a cut beam or a
// no-return beam says nothing about its end cell). As in GMapping, a cell crossed by several
// beams of one scan (near the laser) is updated once per beam; clamping bounds the effect.
void InsertScan(OccupancyGrid& grid, const Pose2& laser_pose, const LaserScan& scan,
                const ScanInsertionParams& params) {
  const CellIndex origin = grid.WorldToCell(laser_pose.translation());
  const long miss = OccupancyGrid::ToSteps(grid.params().log_odds_miss);
  const long hit = OccupancyGrid::ToSteps(grid.params().log_odds_hit);
  const int n = static_cast<int>(scan.ranges_m.size());
  // The end cells first: every one is checked against the grid's extent, and the scan's
  // bounding box against max_cells, before a single cell is written (a fine resolution would
  // otherwise allocate tile after tile along every beam before the table's limit is reached).
  std::vector<CellIndex> ends(static_cast<std::size_t>(n));
  std::vector<bool> traced(static_cast<std::size_t>(n), false);
  CellIndex lo = origin;
  CellIndex hi = origin;
  for (int i = 0; i < n; ++i) {
    const double range = scan.ranges_m[i];
    if (!std::isfinite(range) || range <= 0.0) continue;
    const double reach = scan.IsReturn(i) ? params.usable_range_m
                                          : std::min(params.usable_range_m,
                                                     params.no_return_ray_length_m);
    if (reach <= 0.0) continue;
    const double length = std::min(range, reach);
    const double angle = laser_pose.theta() + scan.BeamAngle(i);
    const Eigen::Vector2d end =
        laser_pose.translation() + length * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const CellIndex c = grid.WorldToCell(end);
    ends[i] = c;
    traced[i] = true;
    lo = {std::min(lo.x, c.x), std::min(lo.y, c.y)};
    hi = {std::max(hi.x, c.x), std::max(hi.y, c.y)};
  }
  const double box_cells = (double(hi.x) - lo.x + 1.0) * (double(hi.y) - lo.y + 1.0);
  if (box_cells > double(grid.params().max_cells)) {
    std::ostringstream msg;
    msg << "InsertScan: one scan covers " << (hi.x - lo.x + 1) << " x " << (hi.y - lo.y + 1)
        << " cells at resolution " << grid.resolution() << " m (" << box_cells
        << " cells), more than the limit max_cells = " << grid.params().max_cells
        << "; raise OccupancyGridParams::max_cells (grid --max-map-cells) or the resolution";
    throw std::length_error(msg.str());
  }
  const auto is_hit = [&](int i) {
    return traced[i] && scan.IsReturn(i) && scan.ranges_m[i] <= params.usable_range_m;
  };
  if (!params.misses_spare_scan_hits) {
    for (int i = 0; i < n; ++i) {
      if (!traced[i]) continue;
      TraceMisses(grid, origin, ends[i], miss);
      if (is_hit(i)) grid.UpdateSteps(ends[i], hit);
    }
    return;
  }
  // Sparing the hit cells from this scan's misses is the same as letting the misses fall, then
  // giving each hit cell back its value from before the scan: a read and a write per hit cell
  // instead of a membership test per crossed cell.
  std::vector<std::pair<CellIndex, long>> before;
  before.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    if (is_hit(i)) before.emplace_back(ends[i], grid.LogOddsSteps(ends[i]));
  }
  for (int i = 0; i < n; ++i) {
    if (!traced[i]) continue;
    TraceMisses(grid, origin, ends[i], miss);
  }
  for (const auto& [cell, steps] : before) {  // every read came before any write
    const long change = steps - grid.LogOddsSteps(cell);
    if (change != 0) grid.UpdateSteps(cell, change);
  }
  for (int i = 0; i < n; ++i) {
    if (is_hit(i)) grid.UpdateSteps(ends[i], hit);
  }
}

}  // namespace slamkit
