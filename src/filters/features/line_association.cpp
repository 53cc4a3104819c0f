#include "slamkit/filters/features/line_association.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "slamkit/features/line_fit.hpp"

namespace slamkit {

int LineMap::Add(int block, const PolarLine& line, const Eigen::Vector2d& a,
                 const Eigen::Vector2d& b) {
  LineExtent extent;
  extent.start_m = a;
  extent.end_m = a;
  entries_.push_back({block, extent, -1});
  Extend(size() - 1, line, a, b);
  return size() - 1;
}

// The extent is kept on the landmark's current line: all four points are projected onto it and
// the two extreme ones along its direction t = (−sin α, cos α) are kept.
void LineMap::Extend(int landmark, const PolarLine& line, const Eigen::Vector2d& a,
                     const Eigen::Vector2d& b) {
  LineExtent& extent = entries_[landmark].extent;
  const Eigen::Vector2d t(-std::sin(line.alpha_rad), std::cos(line.alpha_rad));
  const Eigen::Vector2d points[] = {extent.start_m, extent.end_m, a, b};
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector2d& p : points) {
    lo = std::min(lo, t.dot(p));
    hi = std::max(hi, t.dot(p));
  }
  const Eigen::Vector2d foot =
      line.rho_m * Eigen::Vector2d(std::cos(line.alpha_rad), std::sin(line.alpha_rad));
  extent.start_m = foot + lo * t;
  extent.end_m = foot + hi * t;
}

void LineMap::Merge(int from, int into, const PolarLine& into_line) {
  const LineExtent other = entries_[from].extent;
  Extend(into, into_line, other.start_m, other.end_m);
  entries_[from].merged_into = into;
}

std::vector<AssociationDecision> LineAssociator::Associate(
    const BlockEkf& ekf, int pose_block, const LineLandmarkModel& model, const LineMap& map,
    std::span<const LineSegment> sightings) const {
  std::vector<AssociationDecision> decisions;
  decisions.reserve(sightings.size());
  std::vector<char> taken(map.size(), 0);
  for (const LineSegment& sighting : sightings) {
    const AssociationDecision d = Decide(ekf, pose_block, model, map, sighting, taken);
    if (d.kind == AssociationDecision::Kind::kMatched) taken[d.landmark] = 1;
    decisions.push_back(d);
  }
  return decisions;
}

// SPEC S1 (line association): overlap first (cheap, and what tells collinear walls apart), then
// the Mahalanobis distance on the survivors.
LineAssociator::Nearest LineAssociator::NearestOverlapping(const BlockEkf& ekf, int pose_block,
                                                           const LineLandmarkModel& model,
                                                           const LineMap& map,
                                                           const LineSegment& sighting) const {
  const Pose2 x = ekf.PoseOf(pose_block);
  const Eigen::Vector2d a = x.TransformFrom(sighting.start_m);
  const Eigen::Vector2d b = x.TransformFrom(sighting.end_m);
  const BlockVector z = LineVector(sighting.line);
  const BlockMatrix R = sighting.covariance;
  Nearest nearest;
  for (int k = 0; k < map.size(); ++k) {
    const int blocks[] = {pose_block, map.Block(k)};
    // Outside a compressed area no line overlaps a sighting (FeatureEkfSlam's area holds every
    // line whose extent is within reach): skip the O(a) read of its mean.
    if (!map.Active(k) || !ekf.IsActive(map.Block(k)) || !model.Gate(ekf, blocks)) continue;
    const LineExtent& extent = map.Extent(k);
    const double alpha = ekf.Mean(map.Block(k))[1];
    if (SegmentOverlapM(extent.start_m, extent.end_m, a, b, alpha) < -params_.overlap_margin_m) {
      continue;
    }
    const Linearisation lin = Linearise(model, ekf, blocks, z, R);
    if (std::abs(lin.innovation[0]) < params_.new_min_separation_rho_m &&
        std::abs(lin.innovation[1]) < params_.new_min_separation_alpha_rad) {
      nearest.separated = false;
    }
    const double d2 = ekf.MahalanobisSquared(lin);
    if (d2 < nearest.distance_chi2) {
      nearest.distance_chi2 = d2;
      nearest.landmark = k;
    }
  }
  return nearest;
}

// Nearest neighbour among the compatible landmarks; the rules for a new one.
AssociationDecision LineAssociator::Decide(const BlockEkf& ekf, int pose_block,
                                           const LineLandmarkModel& model, const LineMap& map,
                                           const LineSegment& sighting,
                                           const std::vector<char>& taken) const {
  const Nearest nearest = NearestOverlapping(ekf, pose_block, model, map, sighting);
  AssociationDecision d;
  d.distance_chi2 = nearest.distance_chi2;
  if (nearest.distance_chi2 < params_.gate_chi2 && !taken[nearest.landmark]) {
    d.kind = AssociationDecision::Kind::kMatched;
    d.landmark = nearest.landmark;
    return d;
  }
  const bool can_start = nearest.separated && sighting.LengthM() >= params_.min_new_length_m &&
                         sighting.line.rho_m >= model.min_rho_m();
  d.kind = nearest.distance_chi2 >= params_.new_landmark_chi2 && can_start
               ? AssociationDecision::Kind::kNew
               : AssociationDecision::Kind::kDropped;
  return d;
}

}  // namespace slamkit
