#include <algorithm>
#include <cmath>

#include "fastslam_steps.hpp"

namespace slamkit::fastslam_detail {
namespace {

std::int64_t CellIndex(double coordinate_m, double cell_m) {
  return static_cast<std::int64_t>(std::floor(coordinate_m / cell_m));
}

std::int64_t KeyOf(std::int64_t ix, std::int64_t iy) { return (ix << 32) ^ (iy & 0xffffffff); }

}  // namespace

std::int64_t CellKey(const Eigen::Vector2d& p_m, double cell_m) {
  return KeyOf(CellIndex(p_m.x(), cell_m), CellIndex(p_m.y(), cell_m));
}

void SlotsNear(const SlotGrid& grid, const Eigen::Vector2d& center, double radius_m,
               double cell_m, std::vector<int>& out) {
  out.clear();
  // A square wider than the grid has cells (an unbounded sensor's infinite radius included) is
  // cheaper, and only well defined, as a pass over every cell.
  const double cells_across = 2.0 * radius_m / cell_m + 1.0;
  if (!(cells_across * cells_across < double(grid.size()))) {
    for (const auto& [key, slots] : grid) out.insert(out.end(), slots.begin(), slots.end());
    std::sort(out.begin(), out.end());  // the order of the cell scan does not matter; fix one
    return;
  }
  const std::int64_t hi_x = CellIndex(center.x() + radius_m, cell_m);
  const std::int64_t hi_y = CellIndex(center.y() + radius_m, cell_m);
  for (std::int64_t ix = CellIndex(center.x() - radius_m, cell_m); ix <= hi_x; ++ix) {
    for (std::int64_t iy = CellIndex(center.y() - radius_m, cell_m); iy <= hi_y; ++iy) {
      const auto it = grid.find(KeyOf(ix, iy));
      if (it != grid.end()) out.insert(out.end(), it->second.begin(), it->second.end());
    }
  }
}

}  // namespace slamkit::fastslam_detail
