#include "slamkit/filters/grid/structure_hypothesis.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace slamkit {
namespace {

// The cells of `grid` that the box of h's written cells covers once moved by `transform`.
void MovedBounds(const OccupancyGrid& h, const Pose2& transform, const OccupancyGrid& grid,
                 CellIndex* lo, CellIndex* hi) {
  const double r = h.resolution();
  const CellIndex a = h.min_cell(), b = h.max_cell();
  const std::array<Eigen::Vector2d, 4> corners = {
      Eigen::Vector2d(a.x * r, a.y * r), Eigen::Vector2d((b.x + 1) * r, a.y * r),
      Eigen::Vector2d(a.x * r, (b.y + 1) * r), Eigen::Vector2d((b.x + 1) * r, (b.y + 1) * r)};
  *lo = {1 << 30, 1 << 30};
  *hi = {-(1 << 30), -(1 << 30)};
  for (const Eigen::Vector2d& corner : corners) {
    const CellIndex c = grid.WorldToCell(transform.TransformFrom(corner));
    lo->x = std::min(lo->x, c.x), lo->y = std::min(lo->y, c.y);
    hi->x = std::max(hi->x, c.x), hi->y = std::max(hi->y, c.y);
  }
}

bool OccupiedWithin(const OccupancyGrid& h, const CellIndex& c, int window_cells) {
  for (int dy = -window_cells; dy <= window_cells; ++dy) {
    for (int dx = -window_cells; dx <= window_cells; ++dx) {
      if (h.LogOddsSteps({c.x + dx, c.y + dy}) > 0) return true;
    }
  }
  return false;
}

}  // namespace

void AddMovedHypothesis(const OccupancyGrid& h, const Pose2& transform, OccupancyGrid& layer) {
  if (h.min_cell().x > h.max_cell().x) return;  // nothing predicted
  CellIndex lo, hi;
  MovedBounds(h, transform, layer, &lo, &hi);
  for (int y = lo.y; y <= hi.y; ++y) {
    for (int x = lo.x; x <= hi.x; ++x) {
      const CellIndex c{x, y};
      if (layer.LogOddsSteps(c) != 0) continue;
      const OccupancyGrid::CellValue v =
          h.LogOddsSteps(h.WorldToCell(transform.TransformTo(layer.CellCenter(c))));
      if (v != 0) layer.UpdateSteps(c, v);
    }
  }
}

// SPEC S4 (c), seed Eq. 23.
HypothesisSupport MeasureSupport(const OccupancyGrid& h, const Pose2& to_particle,
                                 const OccupancyGrid& map, const ScanPoints& points,
                                 const Pose2& pose, int window_cells) {
  HypothesisSupport support;
  for (const Eigen::Vector2d& end : points.ends) {
    const Eigen::Vector2d world = pose.TransformFrom(end);
    if (map.LogOddsSteps(map.WorldToCell(world)) != 0) continue;  // z_e: explored already
    const CellIndex in_h = h.WorldToCell(to_particle.TransformTo(world));
    if (h.LogOddsSteps(in_h) == 0) continue;  // neither explored nor predicted
    ++support.beams;
    if (OccupiedWithin(h, in_h, window_cells)) ++support.hits;
  }
  return support;
}

// SPEC S4 (b): the hypothesis-validation model V of seed Section IV.
int UnexploredCells(const OccupancyGrid& h, const Pose2& to_map, const OccupancyGrid& map) {
  int unexplored = 0;
  ForEachKnownCell(h, [&](const CellIndex& c, OccupancyGrid::CellValue) {
    const Eigen::Vector2d p = to_map.TransformFrom(h.CellCenter(c));
    if (map.LogOddsSteps(map.WorldToCell(p)) == 0) ++unexplored;
  });
  return unexplored;
}

}  // namespace slamkit
