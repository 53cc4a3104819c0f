#include "slamkit/filters/grid/scan_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace slamkit {

ScanPoints PrepareScan(const LaserScan& scan, double usable_range_m,
                       const ScanMatcherParams& params) {
  ScanPoints all;
  std::vector<int> beams;
  for (int i = 0; i < static_cast<int>(scan.ranges_m.size()); ++i) {
    if (!scan.IsReturn(i) || scan.ranges_m[i] > usable_range_m) continue;
    const double a = scan.BeamAngle(i);
    const Eigen::Vector2d dir_laser(std::cos(a), std::sin(a));
    all.ends.push_back(scan.laser_offset.TransformFrom(scan.ranges_m[i] * dir_laser));
    all.directions.push_back(scan.laser_offset.rotation() * dir_laser);
    beams.push_back(i);
  }
  // Normals come from every return, so that a stride does not thin out their neighbours.
  all.normals = params.constraints.min_information_ratio > 0.0
                    ? EstimateNormals(all.ends, params.constraints)
                    : std::vector<Eigen::Vector2d>(all.ends.size(), Eigen::Vector2d::Zero());
  const int stride = std::max(1, params.beam_stride);
  if (stride == 1) return all;
  ScanPoints points;
  for (std::size_t k = 0; k < beams.size(); ++k) {
    if (beams[k] % stride != 0) continue;
    points.ends.push_back(all.ends[k]);
    points.directions.push_back(all.directions[k]);
    points.normals.push_back(all.normals[k]);
  }
  return points;
}

namespace {

// The smallest of visit(dx, dy) over the window's cells other than the centre, visited ring by
// ring (Chebyshev distance k from the centre cell) and stopped once no cell further out can be
// nearer: a point of the centre cell is at least (k + 0.5) cells from every cell of ring k + 1.
// The minimum equals a full scan's, so the wide coarse window costs little where a hit is close.
// The margin keeps that true when rounding puts the point a hair outside its cell.
template <class Visit>
double NearestInRings(int window, double resolution, const Visit& visit) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 1; k <= window; ++k) {
    for (int d = -k; d <= k; ++d) best = std::min({best, visit(d, -k), visit(d, k)});
    for (int d = 1 - k; d < k; ++d) best = std::min({best, visit(-k, d), visit(k, d)});
    const double reach = (k + 0.5) * resolution;
    if (best < reach * reach * (1.0 - 1e-9)) break;
  }
  return best;
}

// Squared distance from `end` to the centre of cell (x, y) in the window's rings. Both searches
// below use this one expression (and Eigen's for the end cell), so that a score does not depend
// on which tile a window falls in: GCC fuses a multiply-add where -march offers FMA, and two
// expressions of one distance round differently.
inline double CenterDistanceSq(int x, int y, double resolution, const Eigen::Vector2d& end) {
  const double ex = (x + 0.5) * resolution - end.x();
  const double ey = (y + 0.5) * resolution - end.y();
  return ex * ex + ey * ey;
}

// The nearest-hit search over a window that lies inside one tile: the same cells and tests as the
// general search below with one tile lookup instead of two per cell.
double NearestHitInTile(const OccupancyGrid::CellValue* tile, const OccupancyGrid& grid,
                        const Eigen::Vector2d& end, const CellIndex& c, const CellIndex& f,
                        int window) {
  if (tile == nullptr) return std::numeric_limits<double>::infinity();  // nothing mapped here
  constexpr int kSize = OccupancyGrid::kTileSize, kMask = kSize - 1;
  const int hit0 = (c.y & kMask) * kSize + (c.x & kMask);
  const int free_offset = (f.y - c.y) * kSize + (f.x - c.x);
  const double r = grid.resolution();
  // A point is nearer to the centre of its own cell than to any other cell's centre (the cells are
  // the centres' Voronoi regions), so a hit in the end cell ends the search exactly.
  if (tile[hit0] > 0 && tile[hit0 + free_offset] < 0) {
    return (grid.CellCenter(c) - end).squaredNorm();
  }
  return NearestInRings(window, r, [&](int dx, int dy) {
    const int hit = hit0 + dy * kSize + dx;
    if (tile[hit] <= 0 || tile[hit + free_offset] >= 0) {
      return std::numeric_limits<double>::infinity();
    }
    return CenterDistanceSq(c.x + dx, c.y + dy, r, end);
  });
}

// The cells the search reads: the map alone (its tiles read directly), or a view with a second
// layer under the map. Chosen once per EvaluatePose, so the per-cell reads are inlined.
struct MapOnly {
  const OccupancyGrid& grid;
  static constexpr bool kTiles = true;
  OccupancyGrid::CellValue operator()(const CellIndex& c) const { return grid.LogOddsSteps(c); }
};
struct Layered {
  const GridMapView& view;
  static constexpr bool kTiles = false;
  OccupancyGrid::CellValue operator()(const CellIndex& c) const { return view.LogOddsSteps(c); }
};

// Squared distance from `end` to the nearest cell in the window that is occupied while the cell
// one step back toward the sensor is free; infinity when there is none. `grid` gives the geometry
// (every layer shares it), `cells` the values.
template <class Cells>
double NearestHitDistanceSq(const OccupancyGrid& grid, const Cells& cells,
                            const Eigen::Vector2d& end, const Eigen::Vector2d& direction,
                            int window) {
  const double r = grid.resolution();
  const CellIndex c = grid.WorldToCell(end);
  const CellIndex f = grid.WorldToCell(end - r * direction);
  if constexpr (Cells::kTiles) {
    // f is a neighbour of c, so every cell read lies within window + 1 of c: where that square
    // lies inside c's tile, the tile is looked up once for all of them.
    constexpr int kMask = OccupancyGrid::kTileSize - 1;
    const int margin = window + 1;
    if ((c.x & kMask) >= margin && (c.x & kMask) < kMask + 1 - margin && (c.y & kMask) >= margin &&
        (c.y & kMask) < kMask + 1 - margin) {
      return NearestHitInTile(grid.TileSteps(c), grid, end, c, f, window);
    }
  }
  // A hit in the end cell ends the search exactly (as in NearestHitInTile).
  if (cells(c) > 0 && cells(f) < 0) {
    return (grid.CellCenter(c) - end).squaredNorm();
  }
  return NearestInRings(window, r, [&](int dx, int dy) {
    const CellIndex hit{c.x + dx, c.y + dy};
    if (cells(hit) <= 0 || cells({f.x + dx, f.y + dy}) >= 0) {
      return std::numeric_limits<double>::infinity();
    }
    return CenterDistanceSq(hit.x, hit.y, r, end);
  });
}

// Far above the rounding of a sum of a few thousand terms of at most 1.
constexpr double kPruneMargin = 1e-6;

// A beam's score width (as 1/σ²) and search window in cells.
struct BeamKernel {
  double inv_sigma_sq;
  int window;
};

// ScanMatcherParams::score_sigma_per_m: σ = hypot(score_sigma_m, score_sigma_per_m × range), the
// window wide enough to hold σ. A heading error δ moves an end at range r by r·δ; a kernel that
// grows with r keeps far ends in reach of the wall they belong to.
BeamKernel RangeScaledKernel(const Eigen::Vector2d& end, const ScanMatcherParams& params,
                             double resolution) {
  const double sigma = std::hypot(params.score_sigma_m, params.score_sigma_per_m * end.norm());
  return {1.0 / (sigma * sigma),
          std::max(params.search_cells, static_cast<int>(std::ceil(sigma / resolution)))};
}

// Without kScore the score (an exp per beam) is left at zero, for callers that need only the
// log-likelihood.
// With a finite `min_score`, stops (returning nullopt) once the score plus one per beam left
// stays below min_score by more than the sum's rounding could make up.
template <bool kScore, class Cells>
std::optional<MatchQuality> Evaluate(const OccupancyGrid& grid, const Cells& cells,
                                     const ScanPoints& points, const Pose2& pose,
                                     const ScanMatcherParams& params,
                                     std::vector<std::uint8_t>* hits,
                                     double min_score = -std::numeric_limits<double>::infinity()) {
  if (hits != nullptr) hits->assign(points.ends.size(), 0);
  MatchQuality q;
  const double inv_score = 1.0 / (params.score_sigma_m * params.score_sigma_m);
  const double inv_like = 0.5 / (params.likelihood_sigma_m * params.likelihood_sigma_m);
  // A beam with no hit in its window counts as far as the window reaches.
  const double miss_sq = std::pow((params.search_cells + 1) * grid.resolution(), 2);
  const Eigen::Matrix2d R = pose.rotation();
  const Eigen::Vector2d t = pose.translation();
  const bool scaled = params.score_sigma_per_m > 0.0;
  for (std::size_t i = 0; i < points.ends.size(); ++i) {
    const BeamKernel kernel = scaled ? RangeScaledKernel(points.ends[i], params, grid.resolution())
                                     : BeamKernel{inv_score, params.search_cells};
    const double d_sq = NearestHitDistanceSq(grid, cells, R * points.ends[i] + t,
                                             R * points.directions[i], kernel.window);
    if (std::isfinite(d_sq)) {
      if (hits != nullptr) (*hits)[i] = 1;
      ++q.matched;
      if constexpr (kScore) q.score += std::exp(-d_sq * kernel.inv_sigma_sq);
      q.log_likelihood -= std::min(d_sq, miss_sq) * inv_like;
    } else {
      q.log_likelihood -= miss_sq * inv_like;
    }
    if constexpr (kScore) {
      const double left = double(points.ends.size() - i - 1);
      if (q.score + left < min_score - kPruneMargin) return std::nullopt;
    }
  }
  return q;
}

}  // namespace

MatchQuality EvaluatePose(const GridMapView& grid, const ScanPoints& points, const Pose2& pose,
                          const ScanMatcherParams& params, std::vector<std::uint8_t>* hits) {
  if (grid.second == nullptr) {
    return *Evaluate<true>(grid.map, MapOnly{grid.map}, points, pose, params, hits);
  }
  return *Evaluate<true>(grid.map, Layered{grid}, points, pose, params, hits);
}

std::optional<MatchQuality> EvaluatePoseAbove(const GridMapView& grid, const ScanPoints& points,
                                              const Pose2& pose, const ScanMatcherParams& params,
                                              double min_score) {
  if (grid.second == nullptr) {
    return Evaluate<true>(grid.map, MapOnly{grid.map}, points, pose, params, nullptr, min_score);
  }
  return Evaluate<true>(grid.map, Layered{grid}, points, pose, params, nullptr, min_score);
}

double ScanLogLikelihood(const GridMapView& grid, const ScanPoints& points, const Pose2& pose,
                         const ScanMatcherParams& params) {
  if (grid.second == nullptr) {
    return Evaluate<false>(grid.map, MapOnly{grid.map}, points, pose, params, nullptr)
        ->log_likelihood;
  }
  return Evaluate<false>(grid.map, Layered{grid}, points, pose, params, nullptr)->log_likelihood;
}

}  // namespace slamkit
