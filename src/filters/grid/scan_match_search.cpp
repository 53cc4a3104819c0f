// The scan matcher's search (SPEC S4): the coarse pass with its heading sweep, the hill climb,
// the widened and rescued matches, and the directions the match leaves to the guess. How a pose
// is scored against the map is in scan_matcher.cpp.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "slamkit/core/angle.hpp"
#include "slamkit/filters/grid/match_constraints.hpp"
#include "slamkit/filters/grid/scan_matcher.hpp"

namespace slamkit {

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
      const double penalty = PriorPenalty(initial, moves[i], params);
      const std::optional<MatchQuality> q =
          EvaluatePoseAbove(grid, points, moves[i], params, best_objective + penalty);
      if (!q) continue;  // its score cannot beat the best
      const double objective = q->score - penalty;
      if (objective > best_objective) {
        best.pose = moves[i];
        best.quality = *q;
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
      const std::optional<MatchQuality> q =
          EvaluatePoseAbove(grid, coarse_points, turned, coarse, best_score);
      if (q && q->score > best_score) {
        best = turned;
        best_score = q->score;
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
