#include "slamkit/filters/grid/scan_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "slamkit/core/angle.hpp"

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
    const double ex = (c.x + dx + 0.5) * r - end.x();
    const double ey = (c.y + dy + 0.5) * r - end.y();
    return ex * ex + ey * ey;
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
    return (grid.CellCenter(hit) - end).squaredNorm();
  });
}

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
template <bool kScore, class Cells>
MatchQuality Evaluate(const OccupancyGrid& grid, const Cells& cells, const ScanPoints& points,
                      const Pose2& pose, const ScanMatcherParams& params,
                      std::vector<std::uint8_t>* hits) {
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
  }
  return q;
}

}  // namespace

MatchQuality EvaluatePose(const GridMapView& grid, const ScanPoints& points, const Pose2& pose,
                          const ScanMatcherParams& params, std::vector<std::uint8_t>* hits) {
  if (grid.second == nullptr) {
    return Evaluate<true>(grid.map, MapOnly{grid.map}, points, pose, params, hits);
  }
  return Evaluate<true>(grid.map, Layered{grid}, points, pose, params, hits);
}

double ScanLogLikelihood(const GridMapView& grid, const ScanPoints& points, const Pose2& pose,
                         const ScanMatcherParams& params) {
  if (grid.second == nullptr) {
    return Evaluate<false>(grid.map, MapOnly{grid.map}, points, pose, params, nullptr)
        .log_likelihood;
  }
  return Evaluate<false>(grid.map, Layered{grid}, points, pose, params, nullptr).log_likelihood;
}

namespace {

// The prior's penalty (score units) for moving from `initial` to `pose`.
double PriorPenalty(const Pose2& initial, const Pose2& pose, const ScanMatcherParams& params) {
  double penalty = 0.0;
  if (params.prior_sigma_xy_m > 0.0) {
    penalty += (pose.translation() - initial.translation()).squaredNorm() /
               (params.prior_sigma_xy_m * params.prior_sigma_xy_m);
  }
  if (params.prior_sigma_theta_rad > 0.0) {
    penalty +=
        std::pow(WrapAngle(pose.theta() - initial.theta()) / params.prior_sigma_theta_rad, 2);
  }
  return penalty;
}

MatchResult HillClimb(const GridMapView& grid, const ScanPoints& points, const Pose2& initial,
                      const ScanMatcherParams& params) {
  MatchResult best{initial, EvaluatePose(grid, points, initial, params), false, {}};
  double best_objective = best.quality.score;
  double lin = params.linear_step_m, ang = params.angular_step_rad;
  int refinements = 0;
  // The move back to where the last step came from scored lower already (moves i and i ^ 1 are
  // opposite), so it is not scored again.
  int came_back = -1;
  while (refinements <= params.refinements) {
    const Pose2 from = best.pose;
    const Pose2 moves[6] = {
        {from.x() + lin, from.y(), from.theta()}, {from.x() - lin, from.y(), from.theta()},
        {from.x(), from.y() + lin, from.theta()}, {from.x(), from.y() - lin, from.theta()},
        {from.x(), from.y(), from.theta() + ang}, {from.x(), from.y(), from.theta() - ang}};
    int taken = -1;
    for (int i = 0; i < 6; ++i) {
      if (i == came_back) continue;
      const MatchQuality q = EvaluatePose(grid, points, moves[i], params);
      const double objective = q.score - PriorPenalty(initial, moves[i], params);
      if (objective > best_objective) {
        best.pose = moves[i];
        best.quality = q;
        best_objective = objective;
        taken = i;
      }
    }
    came_back = taken < 0 ? -1 : taken ^ 1;
    if (taken < 0) {
      lin *= 0.5;
      ang *= 0.5;
      ++refinements;
    }
  }
  return best;
}

ScanPoints EveryNth(const ScanPoints& points, int n) {
  ScanPoints out;
  for (std::size_t i = 0; i < points.ends.size(); i += std::max(1, n)) {
    out.ends.push_back(points.ends[i]);
    out.directions.push_back(points.directions[i]);
    if (i < points.normals.size()) out.normals.push_back(points.normals[i]);
  }
  return out;
}

// SPEC S4 refined by Zhang, Kaess and Singh 2016 (solution remapping): the directions that the
// beams matched at `best` leave unconstrained go back to the guess, and the match is scored again
// where it now lies.
void KeepGuessWhereUnconstrained(const GridMapView& grid, const ScanPoints& points,
                                 const Pose2& initial, const ScanMatcherParams& params,
                                 MatchResult* best) {
  // Points built without normals (by hand) say nothing about their constraints.
  if (params.constraints.min_information_ratio <= 0.0 ||
      points.normals.size() != points.ends.size()) {
    return;
  }
  std::vector<std::uint8_t> hits;
  EvaluatePose(grid, points, best->pose, params, &hits);
  const MatchInformation info = ComputeMatchInformation(points.ends, points.normals, hits);
  best->constraints = FindConstraints(info, params.constraints);
  if (best->constraints.unconstrained == 0) return;
  best->pose = KeepGuessAlong(initial, best->pose, best->constraints);
  best->quality = EvaluatePose(grid, points, best->pose, params);
}

// The heading of `initial` turned by the multiple of the sweep's step that scores best (the
// smallest turn on ties), scored as the coarse pass scores.
Pose2 SweepHeading(const GridMapView& grid, const ScanPoints& coarse_points, const Pose2& initial,
                   const ScanMatcherParams& coarse) {
  const int steps = int(coarse.heading_sweep_rad / coarse.heading_sweep_step_rad);
  Pose2 best = initial;
  double best_score = EvaluatePose(grid, coarse_points, initial, coarse).score;
  for (int k = 1; k <= steps; ++k) {
    for (double sign : {-1.0, 1.0}) {
      const Pose2 turned(initial.x(), initial.y(),
                         initial.theta() + sign * k * coarse.heading_sweep_step_rad);
      const double score = EvaluatePose(grid, coarse_points, turned, coarse).score;
      if (score > best_score) {
        best = turned;
        best_score = score;
      }
    }
  }
  return best;
}

// The coarse pass (if any) from `initial`: where the fine pass should start.
Pose2 CoarseStart(const GridMapView& grid, const ScanPoints& points, const Pose2& initial,
                  const ScanMatcherParams& params) {
  if (!params.coarse_pass) return initial;
  ScanMatcherParams coarse = params;
  coarse.search_cells = params.coarse_search_cells;
  coarse.score_sigma_m = params.coarse_score_sigma_m;
  coarse.score_sigma_per_m = params.coarse_score_sigma_per_m;
  coarse.refinements = params.coarse_refinements;
  const ScanPoints coarse_points = EveryNth(points, params.coarse_beam_stride);
  const Pose2 start = params.heading_sweep_rad > 0.0
                          ? SweepHeading(grid, coarse_points, initial, coarse)
                          : initial;
  return HillClimb(grid, coarse_points, start, coarse).pose;
}

// The widened search: the whole climb (coarse and fine) from each of the other headings; the best
// match found replaces `best` if it scores higher.
void WidenHeadings(const GridMapView& grid, const ScanPoints& points, const Pose2& initial,
                   const ScanMatcherParams& params, MatchResult* best) {
  for (int k = 1; k <= params.widen_heading_starts; ++k) {
    for (double sign : {-1.0, 1.0}) {
      const Pose2 turned(initial.x(), initial.y(),
                         initial.theta() + sign * k * params.widen_heading_step_rad);
      const MatchResult other =
          HillClimb(grid, points, CoarseStart(grid, points, turned, params), params);
      if (other.quality.score > best->quality.score) *best = other;
    }
  }
}

// ScanMatcherParams::rescue_sigma_per_m: the whole match again with range-scaled kernels and,
// if that one is accepted, the plain fine climb from where it ended. `rejected` is replaced
// only then.
void RescueMatch(const GridMapView& grid, const ScanPoints& points, const Pose2& initial,
                 const ScanMatcherParams& params, MatchResult* rejected) {
  ScanMatcherParams wide = params;
  wide.score_sigma_per_m = wide.coarse_score_sigma_per_m = params.rescue_sigma_per_m;
  wide.rescue_sigma_per_m = 0.0;
  const MatchResult found = MatchScan(grid, points, initial, wide);
  if (!found.accepted) return;
  ScanMatcherParams fine = params;
  fine.coarse_pass = false;
  fine.widen_below_score_fraction = 0.0;
  fine.rescue_sigma_per_m = 0.0;
  *rejected = MatchScan(grid, points, found.pose, fine);
  rejected->accepted = rejected->rescued = true;
}

}  // namespace

MatchResult MatchScan(const GridMapView& grid, const ScanPoints& points, const Pose2& initial,
                      const ScanMatcherParams& params) {
  MatchResult best = HillClimb(grid, points, CoarseStart(grid, points, initial, params), params);
  const double n = double(points.ends.size());
  if (best.quality.score < params.widen_below_score_fraction * n) {
    WidenHeadings(grid, points, initial, params, &best);
  }
  KeepGuessWhereUnconstrained(grid, points, initial, params, &best);
  best.accepted = !points.ends.empty() && best.quality.score >= params.min_score_fraction * n;
  if (!best.accepted && params.rescue_sigma_per_m > 0.0) {
    RescueMatch(grid, points, initial, params, &best);
  }
  return best;
}

}  // namespace slamkit
