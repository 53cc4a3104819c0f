// The map image every grid run writes (map.pgm, the figure's raster): RenderOccupancyImage, a tile
// row at a time through a table of the 256 stored values, against the per-cell classification it
// replaced (a tile lookup and an exp per cell), measured in the same run on the same grid.

#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "slamkit/io/grid_writers.hpp"
#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {
namespace {

// A square of side `cells` around the origin, three quarters of it written (the rest unknown, as
// a map's corners are), with log-odds from free to occupied.
OccupancyGrid RandomMap(int cells) {
  OccupancyGrid grid({.resolution_m = 0.05});
  std::mt19937 random(3);
  std::uniform_real_distribution<float> log_odds(-4.0f, 4.0f);
  std::bernoulli_distribution written(0.75);
  for (int y = -cells / 2; y < cells / 2; ++y) {
    for (int x = -cells / 2; x < cells / 2; ++x) {
      if (written(random)) grid.Update({x, y}, log_odds(random));
    }
  }
  return grid;
}

const OccupancyGrid& Map() {
  static const OccupancyGrid grid = RandomMap(2000);
  return grid;
}

void BM_RenderOccupancyImage(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(RenderOccupancyImage(Map()).pixels.data());
}
BENCHMARK(BM_RenderOccupancyImage)->Unit(benchmark::kMillisecond);

// The reference: each cell classified on its own, as RenderOccupancyImage did before.
void BM_ReferencePerCellImage(benchmark::State& state) {
  const OccupancyGrid& grid = Map();
  const GridImageParams params;
  const int m = params.margin_cells;
  const CellIndex lo{grid.min_cell().x - m, grid.min_cell().y - m};
  const CellIndex hi{grid.max_cell().x + m, grid.max_cell().y + m};
  std::vector<std::uint8_t> pixels;
  for (auto _ : state) {
    pixels.clear();
    for (int y = hi.y; y >= lo.y; --y) {
      for (int x = lo.x; x <= hi.x; ++x) {
        const double p = grid.Probability({x, y});
        pixels.push_back(!grid.IsKnown({x, y})                ? 205
                         : p >= params.occupied_threshold ? 0
                         : p <= params.free_threshold     ? 254
                                                          : 205);
      }
    }
    benchmark::DoNotOptimize(pixels.data());
  }
}
BENCHMARK(BM_ReferencePerCellImage)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slamkit
