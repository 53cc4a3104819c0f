#include "slamkit/features/line_extraction.hpp"

#include <algorithm>
#include <cmath>

namespace slamkit {
namespace {

// A piece of a run during extraction, with its current fit.
struct Piece {
  PointRange range;
  int run = 0;
  LineFit fit;
};

double ChordDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  const Eigen::Vector2d e = b - a;
  const double len = e.norm();
  if (len < 1e-12) return (p - a).norm();
  return std::abs(e.x() * (p.y() - a.y()) - e.y() * (p.x() - a.x())) / len;
}

LineFit FitRange(std::span<const BeamPoint> points, PointRange r,
                 const LineExtractionParams& params) {
  return FitLineTls(points.subspan(r.begin, r.size()), params.sigma_range_m,
                    params.sigma_bearing_rad);
}

// A piece of fewer points than this fits any line exactly, so says nothing about its wall.
constexpr int kMinFitPoints = 3;

bool NearerToFirst(const Piece& first, const Piece& second, const Eigen::Vector2d& p) {
  return std::abs(DistanceToLine(first.fit.line, p)) <=
         std::abs(DistanceToLine(second.fit.line, p));
}

// SPEC S1, feature extraction, step 3b: the end-point fit can cut a few points off at a corner
// (the chord's farthest point is the corner's neighbour on the other wall, and noise can put the
// cut a few beams off). A piece too small to be kept gives its points, from either end, to the
// neighbouring piece of the same run whose line is nearer, as long as they lie within
// split_distance_m of it. What fits neither stays a piece of its own, for the merge or rejection.
std::vector<Piece> DissolveSmallPieces(std::span<const BeamPoint> points, std::vector<Piece> pieces,
                                       const LineExtractionParams& params) {
  const int min_size = std::max(kMinFitPoints, params.min_points);
  auto fits = [&](const Piece* piece, int k) {
    return piece &&
           std::abs(DistanceToLine(piece->fit.line, points[k].p)) <= params.split_distance_m;
  };
  std::vector<Piece> kept;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    Piece piece = pieces[i];
    // Only a neighbour of the same run, large enough to be kept, takes points.
    auto receiver = [&](Piece* p) {
      return p && p->run == piece.run && p->range.size() >= min_size ? p : nullptr;
    };
    Piece* prev = receiver(kept.empty() ? nullptr : &kept.back());
    Piece* next = receiver(i + 1 < pieces.size() ? &pieces[i + 1] : nullptr);
    if (piece.range.size() >= min_size || (!prev && !next)) {
      kept.push_back(piece);
      continue;
    }
    int k = piece.range.begin, m = piece.range.end;
    while (k < m && fits(prev, k) && (!next || NearerToFirst(*prev, *next, points[k].p))) ++k;
    while (m > k && fits(next, m - 1)) --m;
    if (k > piece.range.begin) {
      prev->range.end = k;
      prev->fit = FitRange(points, prev->range, params);
    }
    if (m < piece.range.end) {
      next->range.begin = m;
      next->fit = FitRange(points, next->range, params);
    }
    if (k < m) {
      const PointRange rest{k, m};
      kept.push_back({rest, piece.run, rest.size() >= kMinFitPoints ? FitRange(points, rest, params)
                                                                   : LineFit{}});
    }
  }
  return kept;
}

// Two fits of one wall differ by noise alone: (Δρ, Δα) ~ N(0, C_a + C_b), the fits using disjoint
// beams. A fixed ρ bound would not do: a short piece far away has a large ρ variance.
bool Collinear(const LineFit& a, const LineFit& b, const LineExtractionParams& params) {
  const Eigen::Vector2d d = LineInnovation(a.line, b.line);
  return std::abs(d[1]) < params.merge_max_angle_rad &&
         LineMahalanobis2(a.line, b.line, a.covariance + b.covariance) <
             params.merge_max_mahalanobis2;
}

// A boundary point within three of its own noise σ (range and bearing noise across the beam) of
// the other piece's line could be on either wall; put in the wrong one it biases a short
// segment's fit, so it is left out of both. The corner between them still comes from the lines.
void DropAmbiguousBoundaryPoints(std::span<const BeamPoint> points, Piece* a, Piece* b,
                                 const LineExtractionParams& params) {
  constexpr double kSigmas = 3.0;
  auto ambiguous = [&](int k, const Piece& other) {
    const double sigma_m =
        std::hypot(params.sigma_range_m, points[k].range_m * params.sigma_bearing_rad);
    return std::abs(DistanceToLine(other.fit.line, points[k].p)) < kSigmas * sigma_m;
  };
  if (a->range.size() > kMinFitPoints && ambiguous(a->range.end - 1, *b)) {
    --a->range.end;
    a->fit = FitRange(points, a->range, params);
  }
  if (b->range.size() > kMinFitPoints && ambiguous(b->range.begin, *a)) {
    ++b->range.begin;
    b->fit = FitRange(points, b->range, params);
  }
}

// SPEC S1, feature extraction, step 5: a cut of the end-point fit leaves the point nearest a
// corner on whichever side the chord chose, and one point of the wrong wall biases the other
// wall's fit. Each boundary point moves to the piece whose line it is nearer, then both refit.
// Not between collinear pieces (left unmerged by the residual test): there it would only sort
// the noise into two piles and push the two fits apart.
void SettleBoundaries(std::span<const BeamPoint> points, std::vector<Piece>* pieces,
                      const LineExtractionParams& params) {
  constexpr int kMaxPasses = 3;
  for (std::size_t i = 0; i + 1 < pieces->size(); ++i) {
    Piece& a = (*pieces)[i];
    Piece& b = (*pieces)[i + 1];
    if (a.run != b.run || a.range.end != b.range.begin || a.range.size() < kMinFitPoints ||
        b.range.size() < kMinFitPoints || Collinear(a.fit, b.fit, params)) {
      continue;
    }
    for (int pass = 0; pass < kMaxPasses; ++pass) {
      auto nearer_b = [&](int k) {
        return std::abs(DistanceToLine(b.fit.line, points[k].p)) <
               std::abs(DistanceToLine(a.fit.line, points[k].p));
      };
      bool moved = false;
      // The two pieces share the boundary index, so each move shifts both ends together.
      while (a.range.size() > kMinFitPoints && nearer_b(a.range.end - 1)) {
        --a.range.end, --b.range.begin, moved = true;
      }
      while (b.range.size() > kMinFitPoints && !nearer_b(b.range.begin)) {
        ++a.range.end, ++b.range.begin, moved = true;
      }
      if (!moved) break;
      a.fit = FitRange(points, a.range, params);
      b.fit = FitRange(points, b.range, params);
    }
    DropAmbiguousBoundaryPoints(points, &a, &b, params);
  }
}

// SPEC S1, feature extraction, step 4 (the "merge" of split-and-merge): neighbouring pieces of
// one run that fit the same line are joined, unless the joint fit's residual is too large. The
// one or two points that step 3b could not place (too far from both lines to join either) do
// not stop a merge across them; the joint fit then has to accept them.
std::vector<Piece> MergeCollinear(std::span<const BeamPoint> points, std::vector<Piece> pieces,
                                  const LineExtractionParams& params) {
  std::vector<Piece> merged, unplaced;
  auto flush = [&] {
    for (Piece& u : unplaced) merged.push_back(std::move(u));
    unplaced.clear();
  };
  for (Piece& piece : pieces) {
    if (piece.range.size() < kMinFitPoints) {
      unplaced.push_back(std::move(piece));
      continue;
    }
    if (!merged.empty() && merged.back().run == piece.run &&
        merged.back().range.size() >= kMinFitPoints &&
        Collinear(merged.back().fit, piece.fit, params)) {
      const PointRange joint{merged.back().range.begin, piece.range.end};
      const LineFit fit = FitRange(points, joint, params);
      if (fit.residual_rms_m <= params.max_residual_rms_m) {
        merged.back().range = joint;
        merged.back().fit = fit;
        unplaced.clear();  // inside the joint range now
        continue;
      }
    }
    flush();
    merged.push_back(std::move(piece));
  }
  flush();
  return merged;
}

LineSegment ToSegment(std::span<const BeamPoint> points, const Piece& piece,
                      const LineExtractionParams& params) {
  LineSegment s;
  s.line = piece.fit.line;
  // The wall's own departure from a line, which no beam noise averages away.
  s.covariance = piece.fit.covariance;
  s.covariance(0, 0) += params.wall_sigma_rho_m * params.wall_sigma_rho_m;
  s.covariance(1, 1) += params.wall_sigma_alpha_rad * params.wall_sigma_alpha_rad;
  s.residual_rms_m = piece.fit.residual_rms_m;
  s.num_points = piece.range.size();
  s.first_beam = points[piece.range.begin].beam;
  s.last_beam = points[piece.range.end - 1].beam;
  s.start_m = ProjectOntoLine(s.line, points[piece.range.begin].p);
  s.end_m = ProjectOntoLine(s.line, points[piece.range.end - 1].p);
  return s;
}

// SPEC S1, feature extraction, step 6: "minimum points, maximum fit residual".
bool IsSupported(const LineSegment& s, const LineExtractionParams& params) {
  return s.num_points >= std::max(kMinFitPoints, params.min_points) &&
         s.LengthM() >= params.min_length_m &&
         s.residual_rms_m <= params.max_residual_rms_m;
}

}  // namespace

// SPEC S1, feature extraction, step 1.
std::vector<BeamPoint> ScanToBeamPoints(const LaserScan& scan, double max_usable_range_m) {
  std::vector<BeamPoint> points;
  for (int i = 0; i < static_cast<int>(scan.ranges_m.size()); ++i) {
    if (!scan.IsReturn(i) || !(scan.ranges_m[i] < max_usable_range_m)) continue;
    BeamPoint b;
    b.range_m = scan.ranges_m[i];
    b.bearing_rad = scan.BeamAngle(i);
    b.p = b.range_m * Eigen::Vector2d(std::cos(b.bearing_rad), std::sin(b.bearing_rad));
    b.beam = i;
    points.push_back(b);
  }
  return points;
}

// SPEC S1, feature extraction, step 2.
std::vector<PointRange> SplitAtGaps(std::span<const BeamPoint> points, double max_gap_m) {
  std::vector<PointRange> runs;
  int begin = 0;
  const int n = static_cast<int>(points.size());
  for (int i = 1; i <= n; ++i) {
    if (i == n || (points[i].p - points[i - 1].p).norm() > max_gap_m) {
      if (i > begin) runs.push_back({begin, i});
      begin = i;
    }
  }
  return runs;
}

// SPEC S1, feature extraction, step 3 (iterative end-point fit, Duda & Hart 1973).
std::vector<PointRange> SplitByEndpointFit(std::span<const BeamPoint> points, PointRange run,
                                           double split_distance_m) {
  std::vector<PointRange> pieces, todo{run};
  while (!todo.empty()) {
    const PointRange r = todo.back();
    todo.pop_back();
    int farthest = -1;
    double farthest_m = split_distance_m;
    for (int k = r.begin + 1; k < r.end - 1; ++k) {
      const double d = ChordDistance(points[r.begin].p, points[r.end - 1].p, points[k].p);
      if (d > farthest_m) farthest = k, farthest_m = d;
    }
    if (farthest < 0) {
      pieces.push_back(r);
    } else {
      todo.push_back({r.begin, farthest});
      todo.push_back({farthest, r.end});
    }
  }
  std::sort(pieces.begin(), pieces.end(),
            [](const PointRange& a, const PointRange& b) { return a.begin < b.begin; });
  return pieces;
}

// SPEC S1, feature extraction: split-and-merge with TLS fits (the extractor Nguyen et al., IROS
// 2005, found both fast and correct among the common ones for 2D laser scans).
std::vector<LineSegment> ExtractLines(const LaserScan& scan, const LineExtractionParams& params) {
  const std::vector<BeamPoint> points = ScanToBeamPoints(scan, params.max_usable_range_m);
  std::vector<Piece> pieces;
  const std::vector<PointRange> runs = SplitAtGaps(points, params.max_gap_m);
  for (int run = 0; run < static_cast<int>(runs.size()); ++run) {
    for (const PointRange& r : SplitByEndpointFit(points, runs[run], params.split_distance_m)) {
      Piece piece{r, run, {}};
      if (r.size() >= kMinFitPoints) piece.fit = FitRange(points, r, params);
      pieces.push_back(piece);
    }
  }
  pieces = DissolveSmallPieces(points, std::move(pieces), params);
  pieces = MergeCollinear(points, std::move(pieces), params);
  SettleBoundaries(points, &pieces, params);
  std::vector<LineSegment> segments;
  for (const Piece& piece : pieces) {
    LineSegment s = ToSegment(points, piece, params);
    if (IsSupported(s, params)) segments.push_back(s);
  }
  return segments;
}

}  // namespace slamkit
