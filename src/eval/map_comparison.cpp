#include "slamkit/eval/map_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace slamkit {
namespace {

enum class CellClass { kFree, kOccupied, kUnknown };

struct Reading {
  CellClass cell = CellClass::kUnknown;
  double p = 0.5;  // clamped occupancy; the prior for an unknown cell
};

Reading Read(std::uint8_t v, const MapComparisonParams& params) {
  const double p = (255.0 - v) / 255.0;
  Reading r;
  if (p > params.occupied_threshold) r.cell = CellClass::kOccupied;
  if (p < params.free_threshold) r.cell = CellClass::kFree;
  if (r.cell != CellClass::kUnknown) {
    r.p = std::clamp(p, params.probability_floor, 1.0 - params.probability_floor);
  }
  return r;
}

double BernoulliKl(double p, double q) {
  return p * std::log(p / q) + (1.0 - p) * std::log((1.0 - p) / (1.0 - q));
}

// The whole number of cells from `from`'s origin to `to`'s along one axis.
long CellOffset(double from_m, double to_m, double resolution_m) {
  const double cells = (to_m - from_m) / resolution_m;
  const double whole = std::round(cells);
  if (std::abs(cells - whole) > 1e-6) {
    throw std::invalid_argument(
        "map comparison: the origins are not a whole number of cells apart");
  }
  return static_cast<long>(whole);
}

void CheckInputs(const OccupancyImage& a, const OccupancyImage& b, const MapComparisonParams& p) {
  const double r = a.resolution_m;
  if (!(r > 0.0) || std::abs(r - b.resolution_m) > 1e-9 * r) {
    throw std::invalid_argument("map comparison: the maps' resolutions differ");
  }
  if (!(0.0 <= p.free_threshold && p.free_threshold < p.occupied_threshold &&
        p.occupied_threshold <= 1.0 && p.probability_floor > 0.0 && p.probability_floor < 0.5 &&
        p.dice_tolerance_cells >= 0 && p.dice_tolerance_cells <= 100)) {
    throw std::invalid_argument(
        "map comparison: need 0 <= free_threshold < occupied_threshold <= 1, 0 < floor < 0.5, "
        "0 <= dice_tolerance_cells <= 100");
  }
}

// Pixel of cell (x, y) counted from the lower-left corner (the image's top row is the largest y).
std::uint8_t At(const OccupancyImage& image, long x, long y) {
  return image.pixels[static_cast<std::size_t>((image.height - 1 - y) * image.width + x)];
}

bool OccupiedNear(const OccupancyImage& image, long x, long y, int k,
                  const MapComparisonParams& params) {
  for (long v = std::max(0L, y - k); v <= std::min<long>(image.height - 1, y + k); ++v) {
    for (long u = std::max(0L, x - k); u <= std::min<long>(image.width - 1, x + k); ++u) {
      if (Read(At(image, u, v), params).cell == CellClass::kOccupied) return true;
    }
  }
  return false;
}

// Ψ with a tolerance: the occupied cells of each map (over the overlap) that have an occupied
// cell of the other within k cells, over all occupied cells. k = 0 is Eq. 5.
double TolerantDice(const OccupancyImage& first, const OccupancyImage& second, long dx, long dy,
                    long x0, long x1, long y0, long y1, const MapComparisonParams& params) {
  const int k = params.dice_tolerance_cells;
  long matched = 0, occupied = 0;
  for (long y = y0; y < y1; ++y) {
    for (long x = x0; x < x1; ++x) {
      if (Read(At(first, x, y), params).cell == CellClass::kOccupied) {
        ++occupied;
        matched += OccupiedNear(second, x - dx, y - dy, k, params);
      }
      if (Read(At(second, x - dx, y - dy), params).cell == CellClass::kOccupied) {
        ++occupied;
        matched += OccupiedNear(first, x, y, k, params);
      }
    }
  }
  return occupied > 0 ? double(matched) / double(occupied) : 0.0;
}

}  // namespace

// SPEC S4, Eqs. 5 and 24, over the cells of the two maps' overlap.
MapComparison CompareMaps(const OccupancyImage& first, const OccupancyImage& second,
                          const MapComparisonParams& params) {
  CheckInputs(first, second, params);
  const long dx = CellOffset(first.origin_m.x(), second.origin_m.x(), first.resolution_m);
  const long dy = CellOffset(first.origin_m.y(), second.origin_m.y(), first.resolution_m);
  const long x0 = std::max(0L, dx), x1 = std::min<long>(first.width, dx + second.width);
  const long y0 = std::max(0L, dy), y1 = std::min<long>(first.height, dy + second.height);
  MapComparison out;
  long same = 0, occupied_first = 0, occupied_second = 0, occupied_both = 0;
  for (long y = y0; y < y1; ++y) {
    for (long x = x0; x < x1; ++x) {
      const Reading a = Read(At(first, x, y), params);
      const Reading b = Read(At(second, x - dx, y - dy), params);
      ++out.cells;
      occupied_first += a.cell == CellClass::kOccupied;
      occupied_second += b.cell == CellClass::kOccupied;
      occupied_both += a.cell == CellClass::kOccupied && b.cell == CellClass::kOccupied;
      if (a.cell == CellClass::kUnknown && b.cell == CellClass::kUnknown) continue;
      ++out.known_cells;
      same += a.cell == b.cell;
      out.kl_divergence += BernoulliKl(a.p, b.p);
    }
  }
  out.cell_accuracy = out.known_cells > 0 ? double(same) / double(out.known_cells) : 0.0;
  const long occupied = occupied_first + occupied_second;
  out.dice_occupied = occupied > 0 ? 2.0 * double(occupied_both) / double(occupied) : 0.0;
  if (params.dice_tolerance_cells > 0) {
    out.dice_occupied = TolerantDice(first, second, dx, dy, x0, x1, y0, y1, params);
  }
  return out;
}

}  // namespace slamkit
