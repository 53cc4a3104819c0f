#include "slamkit/planning/grid_frontiers.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <stdexcept>
#include <utility>

namespace slamkit {
namespace {

// The search window: the written cells and a ring of one around them, so that free cells on
// the written border see the unknown beyond.
struct Window {
  int x0 = 0, y0 = 0, width = 0, height = 0;
  std::size_t Index(int x, int y) const {
    return static_cast<std::size_t>(y - y0) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(x - x0);
  }
  bool Contains(int x, int y) const {
    return x >= x0 && y >= y0 && x < x0 + width && y < y0 + height;
  }
};

bool Unexplored(const OccupancyGrid& grid, const CellIndex& c, const GridFrontierParams& p) {
  if (!grid.IsKnown(c)) return true;
  const double probability = grid.Probability(c);
  return probability >= p.free_probability && probability <= p.occupied_probability;
}

// The 8-connected region of frontier cells holding `seed`, marked in `taken`.
FrontierRegion GrowRegion(const OccupancyGrid& grid, const Window& w, CellIndex seed,
                          const std::vector<char>& frontier, std::vector<char>& taken) {
  FrontierRegion region;
  std::vector<CellIndex> stack = {seed};
  taken[w.Index(seed.x, seed.y)] = 1;
  while (!stack.empty()) {
    const CellIndex c = stack.back();
    stack.pop_back();
    region.cells.push_back(c);
    region.centroid_m += grid.CellCenter(c);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = c.x + dx, y = c.y + dy;
        if (!w.Contains(x, y) || !frontier[w.Index(x, y)] || taken[w.Index(x, y)]) continue;
        taken[w.Index(x, y)] = 1;
        stack.push_back({x, y});
      }
    }
  }
  region.centroid_m /= static_cast<double>(region.cells.size());
  return region;
}

}  // namespace

bool IsFrontierCell(const OccupancyGrid& grid, const CellIndex& c, const GridFrontierParams& p) {
  if (!grid.IsKnown(c) || grid.Probability(c) >= p.free_probability) return false;
  constexpr std::array<std::array<int, 2>, 4> kSides = {{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
  for (const auto& [dx, dy] : kSides) {
    if (Unexplored(grid, {c.x + dx, c.y + dy}, p)) return true;
  }
  return false;
}

std::vector<FrontierRegion> FindFrontierRegions(const OccupancyGrid& grid,
                                                const GridFrontierParams& params) {
  if (!(params.free_probability > 0.0 && params.free_probability <= params.occupied_probability &&
        params.occupied_probability < 1.0) ||
      params.min_region_cells < 1) {
    throw std::invalid_argument(
        "grid frontiers: need 0 < free_probability <= occupied_probability < 1, "
        "min_region_cells >= 1");
  }
  const CellIndex lo = grid.min_cell(), hi = grid.max_cell();
  if (lo.x > hi.x || lo.y > hi.y) return {};
  const Window w{lo.x - 1, lo.y - 1, hi.x - lo.x + 3, hi.y - lo.y + 3};
  std::vector<char> frontier(static_cast<std::size_t>(w.width) * w.height, 0);
  for (int y = lo.y; y <= hi.y; ++y) {
    for (int x = lo.x; x <= hi.x; ++x) {
      frontier[w.Index(x, y)] = IsFrontierCell(grid, {x, y}, params);
    }
  }
  std::vector<char> taken(frontier.size(), 0);
  std::vector<FrontierRegion> regions;
  for (int y = lo.y; y <= hi.y; ++y) {
    for (int x = lo.x; x <= hi.x; ++x) {
      if (!frontier[w.Index(x, y)] || taken[w.Index(x, y)]) continue;
      FrontierRegion region = GrowRegion(grid, w, {x, y}, frontier, taken);
      if (static_cast<int>(region.cells.size()) >= params.min_region_cells) {
        regions.push_back(std::move(region));
      }
    }
  }
  std::stable_sort(regions.begin(), regions.end(), [](const auto& a, const auto& b) {
    return a.cells.size() > b.cells.size();
  });
  return regions;
}

}  // namespace slamkit
