#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"

namespace slamkit {

// A cell of the grid: integer coordinates, cell (0, 0) covers [0, r) × [0, r) in metres.
struct CellIndex {
  int x = 0;
  int y = 0;
  friend bool operator==(const CellIndex&, const CellIndex&) = default;
};

struct OccupancyGridParams {
  double resolution_m = 0.05;
  float log_odds_hit = 0.85f;    // ≈ ln(0.7 / 0.3)
  float log_odds_miss = -0.4f;   // ≈ ln(0.4 / 0.6)
  float log_odds_min = -4.0f;    // clamping keeps cells able to change their mind (|·| ≤ 7.9)
  float log_odds_max = 4.0f;
  // Limits, checked before anything is allocated (a bad pose or resolution would otherwise
  // allocate until the process dies). A point farther than max_extent_m from the origin on
  // either axis cannot be mapped (WorldToCell throws std::out_of_range); the extent is also
  // capped at kMaxCellCoordinate cells, so a fine resolution shrinks it. A write that would grow
  // the tile table beyond max_cells cells (1 byte each once written) throws std::length_error.
  // Raise them here (or with the command line's --max-map-extent / --max-map-cells).
  double max_extent_m = 1.0e5;
  std::uint64_t max_cells = std::uint64_t{1} << 30;
};

// An occupancy grid in log-odds (0 = unknown) that grows as it is written, stored in square
// tiles held by shared pointers: copying a grid shares every tile, and a write to a shared tile
// copies that tile only (copy-on-write). Particles of a particle filter can thus each own a map
// while sharing the parts they have not changed.
class OccupancyGrid {
 public:
  static constexpr int kTileBits = 6;  // 64 × 64 cells per tile
  static constexpr int kTileSize = 1 << kTileBits;
  // A cell's log-odds in 8-bit fixed point, kLogOddsStep = 1/32 per step (±3.97 representable):
  // a quarter of the memory of floats, which matters with one map per particle (30 particles on
  // Intel peaked at 168 MB with floats, 118 MB with 16 bits) and in the matcher's lookups. The
  // step is far below anything the inverse sensor model can tell apart.
  using CellValue = std::int8_t;

  explicit OccupancyGrid(const OccupancyGridParams& params = {});

  const OccupancyGridParams& params() const { return params_; }
  double resolution() const { return params_.resolution_m; }
  // The largest |cell coordinate| a grid uses: differences of two coordinates (ray lengths) and
  // tile arithmetic then stay far from int overflow.
  static constexpr int kMaxCellCoordinate = 1 << 29;
  // The half-width in metres of the square the grid can map: min(max_extent_m,
  // kMaxCellCoordinate × resolution).
  double extent_m() const { return cell_limit_ * params_.resolution_m; }
  // Inline: scan matching calls these hundreds of thousands of times per scan. Throws
  // std::out_of_range for a point outside ±extent_m() (or not finite), before any conversion
  // to int could overflow.
  CellIndex WorldToCell(const Eigen::Vector2d& p) const {
    const double x = std::floor(p.x() * inverse_resolution_);
    const double y = std::floor(p.y() * inverse_resolution_);
    if (!(std::abs(x) <= cell_limit_ && std::abs(y) <= cell_limit_)) [[unlikely]] {
      ThrowOutsideExtent(p);
    }
    return {static_cast<int>(x), static_cast<int>(y)};
  }
  Eigen::Vector2d CellCenter(const CellIndex& c) const {
    return {(c.x + 0.5) * params_.resolution_m, (c.y + 0.5) * params_.resolution_m};
  }

  // 0 outside the written area. Stored to a resolution of kLogOddsStep.
  float LogOdds(const CellIndex& c) const { return kLogOddsStep * LogOddsSteps(c); }
  // The stored value in kLogOddsStep units: its sign is all that occupied/free tests need.
  CellValue LogOddsSteps(const CellIndex& c) const {
    const CellValue* tile = TileSteps(c);
    constexpr int kMask = kTileSize - 1;
    return tile == nullptr ? 0 : tile[(c.y & kMask) * kTileSize + (c.x & kMask)];
  }
  // The steps of the whole tile holding `c`, row-major (kTileSize per row, the tile's lowest
  // cell first), or nullptr where nothing was written (every cell 0): a caller reading a small
  // neighbourhood inside one tile looks the tile up once.
  const CellValue* TileSteps(const CellIndex& c) const {
    const unsigned ix = static_cast<unsigned>((c.x >> kTileBits) - tile_min_.x);
    const unsigned iy = static_cast<unsigned>((c.y >> kTileBits) - tile_min_.y);
    if (ix >= static_cast<unsigned>(tile_extent_.x) ||
        iy >= static_cast<unsigned>(tile_extent_.y)) {
      return nullptr;
    }
    const Tile* tile = tiles_[std::size_t(iy) * std::size_t(tile_extent_.x) + ix].get();
    return tile == nullptr ? nullptr : tile->data();
  }
  double Probability(const CellIndex& c) const { return StepsProbability(LogOddsSteps(c)); }
  // The occupancy of a stored value (LogOddsSteps): a table over the 256 values classifies cells
  // as Probability does, without an exp per cell.
  static double StepsProbability(CellValue steps) {
    return 1.0 - 1.0 / (1.0 + std::exp(static_cast<double>(kLogOddsStep * steps)));
  }
  bool IsKnown(const CellIndex& c) const { return LogOdds(c) != 0.0f; }
  // Adds `delta` to the cell's log-odds, clamped to [log_odds_min, log_odds_max] (and to what a
  // cell can hold).
  void Update(const CellIndex& c, float delta) { UpdateSteps(c, ToSteps(delta)); }
  // The same with the change already in kLogOddsStep units (ToSteps), for loops over many cells.
  void UpdateSteps(const CellIndex& c, long delta_steps);
  static long ToSteps(float delta) { return std::lround(delta / kLogOddsStep); }
  // UpdateSteps(c, delta_steps) for every cell c that `for_each_cell(write)` passes to write, in
  // order. The tile of the last cell is kept, so a run of cells inside one tile (a ray crosses a
  // tile in up to 64 steps) looks it up, and checks whether it is shared, once.
  template <class ForEachCell>
  void UpdateStepsAlong(const ForEachCell& for_each_cell, long delta_steps);

  // Inclusive bounds of the cells written so far (min > max when nothing was written).
  CellIndex min_cell() const { return min_cell_; }
  CellIndex max_cell() const { return max_cell_; }
  std::size_t TileCount() const;
  std::size_t SharedTileCount() const;  // tiles also referenced by another grid

 private:
  using Tile = std::array<CellValue, kTileSize * kTileSize>;
  static constexpr float kLogOddsStep = 1.0f / 32.0f;
  static constexpr long kMaxSteps = 127;
  std::shared_ptr<Tile>* FindTileSlot(int tx, int ty);
  [[noreturn]] void ThrowOutsideExtent(const Eigen::Vector2d& p) const;
  Tile& MutableTile(int tx, int ty);
  void ExtendBounds(int x, int y) {
    if (min_cell_.x > max_cell_.x) {  // the first write
      min_cell_.x = max_cell_.x = x;
      min_cell_.y = max_cell_.y = y;
      return;
    }
    if (x < min_cell_.x) min_cell_.x = x;
    if (y < min_cell_.y) min_cell_.y = y;
    if (x > max_cell_.x) max_cell_.x = x;
    if (y > max_cell_.y) max_cell_.y = y;
  }

  OccupancyGridParams params_;
  double inverse_resolution_;
  double cell_limit_;  // the largest |cell coordinate| WorldToCell returns
  long min_steps_;  // the clamping bounds in kLogOddsStep units
  long max_steps_;
  // Tiles in a row-major table over the tile range [tile_min_, tile_min_ + tile_extent_).
  std::vector<std::shared_ptr<Tile>> tiles_;
  CellIndex tile_min_{0, 0};
  CellIndex tile_extent_{0, 0};
  CellIndex min_cell_{1, 1};
  CellIndex max_cell_{0, 0};
};

template <class ForEachCell>
void OccupancyGrid::UpdateStepsAlong(const ForEachCell& for_each_cell, long delta_steps) {
  constexpr int kMask = kTileSize - 1;
  // Locals, not members, inside the loop: a store to a cell (a char type) may alias any member,
  // so members read in the loop would be loaded again after every cell written.
  const long min_steps = min_steps_, max_steps = max_steps_;
  Tile* tile = nullptr;
  int tile_x = 0, tile_y = 0;
  CellIndex lo{std::numeric_limits<int>::max(), std::numeric_limits<int>::max()};
  CellIndex hi{std::numeric_limits<int>::min(), std::numeric_limits<int>::min()};
  for_each_cell([&](const CellIndex& c) {
    const int x = c.x, y = c.y;  // read one int at a time: see UpdateSteps
    if (tile == nullptr || (x >> kTileBits) != tile_x || (y >> kTileBits) != tile_y) {
      tile_x = x >> kTileBits;
      tile_y = y >> kTileBits;
      tile = &MutableTile(tile_x, tile_y);
    }
    CellValue& l = (*tile)[(y & kMask) * kTileSize + (x & kMask)];
    l = static_cast<CellValue>(std::clamp(l + delta_steps, min_steps, max_steps));
    lo = {std::min(lo.x, x), std::min(lo.y, y)};
    hi = {std::max(hi.x, x), std::max(hi.y, y)};
  });
  if (lo.x > hi.x) return;  // no cell written
  ExtendBounds(lo.x, lo.y);
  ExtendBounds(hi.x, hi.y);
}

// Cells on the digital line from `from` to `to` (integer Bresenham), both ends included, in order.
std::vector<CellIndex> RayCells(const CellIndex& from, const CellIndex& to);

struct ScanInsertionParams {
  double usable_range_m = 30.0;  // beams are cut here; a cut beam marks free space only
  // When true, a beam's free-space update skips the cells where another beam of the same scan
  // ends: a ray grazing a wall then no longer erodes the wall cells its neighbours just hit
  // (Cartographer inserts a scan the same way: a cell hit in a scan gets no miss from it).
  bool misses_spare_scan_hits = false;
  // A no-return beam (LaserScan::IsReturn false) marks free space this far only, and never
  // beyond the usable range: a beam that saw nothing may have met glass or a black surface well
  // short of the laser's range (Cartographer's missing_data_ray_length; GMapping skips them).
  double no_return_ray_length_m = std::numeric_limits<double>::infinity();
};

// Inverse sensor model: every beam marks the cells it crosses as free and, if it returned
// within usable range, its end cell as occupied (a no-return beam is cut at
// no_return_ray_length_m as well). `laser_pose` is the laser in the world frame.
void InsertScan(OccupancyGrid& grid, const Pose2& laser_pose, const LaserScan& scan,
                const ScanInsertionParams& params = {});

}  // namespace slamkit
