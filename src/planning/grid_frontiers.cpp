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

// Each stored value's class, from the probability the grid reports for it: free cells, and
// cells that are not explored (unknown, or between the two thresholds).
struct StepClasses {
  std::array<char, 256> free{}, unexplored{};
  explicit StepClasses(const GridFrontierParams& p) {
    for (int s = -128; s <= 127; ++s) {
      const double probability =
          OccupancyGrid::StepsProbability(static_cast<OccupancyGrid::CellValue>(s));
      free[s + 128] = s != 0 && probability < p.free_probability;
      unexplored[s + 128] =
          s == 0 || (probability >= p.free_probability && probability <= p.occupied_probability);
    }
  }
  bool Free(OccupancyGrid::CellValue v) const { return free[v + 128]; }
  bool Unexplored(OccupancyGrid::CellValue v) const { return unexplored[v + 128]; }
  bool Frontier(const OccupancyGrid& grid, const CellIndex& c) const {
    if (!Free(grid.LogOddsSteps(c))) return false;
    constexpr std::array<std::array<int, 2>, 4> kSides = {{{1, 0}, {-1, 0}, {0, 1}, {0, -1}}};
    for (const auto& [dx, dy] : kSides) {
      if (Unexplored(grid.LogOddsSteps({c.x + dx, c.y + dy}))) return true;
    }
    return false;
  }
};

// The frontier cells of the written window in raster order, marked 1 in `mask`: tiles nothing
// was written to hold no free cell and are skipped.
std::vector<CellIndex> MarkFrontierCells(const OccupancyGrid& grid, const Window& w,
                                         const StepClasses& classes, std::vector<char>& mask) {
  constexpr int kTile = OccupancyGrid::kTileSize;
  const CellIndex lo = grid.min_cell(), hi = grid.max_cell();
  std::vector<CellIndex> cells;
  for (int y = lo.y; y <= hi.y; ++y) {
    for (int x = lo.x; x <= hi.x;) {
      const int tile_end = std::min(hi.x + 1, ((x >> OccupancyGrid::kTileBits) + 1) * kTile);
      if (grid.TileSteps({x, y}) == nullptr) {
        x = tile_end;
        continue;
      }
      for (; x < tile_end; ++x) {
        if (!classes.Frontier(grid, {x, y})) continue;
        mask[w.Index(x, y)] = 1;
        cells.push_back({x, y});
      }
    }
  }
  return cells;
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
  return StepClasses(p).Frontier(grid, c);
}

bool InFrontierRegion(const OccupancyGrid& grid, const CellIndex& c, const GridFrontierParams& p) {
  const StepClasses classes(p);
  if (!classes.Frontier(grid, c)) return false;
  std::vector<CellIndex> region = {c};  // small: it stops at min_region_cells
  for (std::size_t i = 0; i < region.size() && static_cast<int>(region.size()) < p.min_region_cells;
       ++i) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const CellIndex n{region[i].x + dx, region[i].y + dy};
        if (std::find(region.begin(), region.end(), n) == region.end() &&
            classes.Frontier(grid, n)) {
          region.push_back(n);
        }
      }
    }
  }
  return static_cast<int>(region.size()) >= p.min_region_cells;
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
  const std::vector<CellIndex> cells = MarkFrontierCells(grid, w, StepClasses(params), frontier);
  std::vector<char> taken(frontier.size(), 0);
  std::vector<FrontierRegion> regions;
  for (const CellIndex& c : cells) {
    if (taken[w.Index(c.x, c.y)]) continue;
    FrontierRegion region = GrowRegion(grid, w, c, frontier, taken);
    if (static_cast<int>(region.cells.size()) >= params.min_region_cells) {
      regions.push_back(std::move(region));
    }
  }
  std::stable_sort(regions.begin(), regions.end(), [](const auto& a, const auto& b) {
    return a.cells.size() > b.cells.size();
  });
  return regions;
}

}  // namespace slamkit
