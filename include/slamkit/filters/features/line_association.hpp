#pragma once

#include <Eigen/Core>
#include <limits>
#include <span>
#include <vector>

#include "slamkit/features/line_extraction.hpp"
#include "slamkit/filters/association/data_association.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/features/line_landmark_model.hpp"

namespace slamkit {

struct LineAssociationParams {
  // Squared Mahalanobis distance of (ρ, α) under which a sighting is compatible with a line
  // landmark (χ²₂ at 99 %), and above which (to every overlapping landmark) it starts a new one
  // (χ²₂ at 99.9 %); between the two it is ambiguous and dropped.
  double gate_chi2 = 9.21;
  double new_landmark_chi2 = 13.82;
  // A sighting whose world segment, projected onto a landmark's line, lies farther than this
  // beyond the landmark's extent is not that landmark (two collinear walls far apart stay two).
  double overlap_margin_m = 0.5;
  // A sighting shorter than this never starts a landmark (it may still update one).
  double min_new_length_m = 1.0;
  // Nor does one within both of these of an overlapping landmark's (ρ, α) (robot frame), however
  // far in Mahalanobis distance: that is the same wall fitted too confidently (a short glimpse
  // through a door, a biased end), not a second wall.
  double new_min_separation_rho_m = 0.2;
  double new_min_separation_alpha_rad = 0.1;
};

// The part of a line landmark seen so far: a world-frame segment on the landmark's line.
struct LineExtent {
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d end_m = Eigen::Vector2d::Zero();
};

// The line landmarks of a BlockEkf: each one's block and its extent, indexed by landmark
// (creation order). The extents are what the segment-overlap test of association reads.
class LineMap {
 public:
  void Clear() { entries_.clear(); }
  // A landmark in block `block` (its current estimate `line`) first seen as world segment
  // [a, b], projected onto `line`; returns its index.
  int Add(int block, const PolarLine& line, const Eigen::Vector2d& a, const Eigen::Vector2d& b);
  // Grows landmark `landmark`'s extent to cover world segment [a, b]: the extreme points of the
  // old extent and [a, b], projected onto `line` (the landmark's current estimate).
  void Extend(int landmark, const PolarLine& line, const Eigen::Vector2d& a,
              const Eigen::Vector2d& b);

  // Landmark `from` is the same wall as `into` (their estimates were fused): `into`'s extent
  // grows to cover `from`'s, and `from` is no longer offered to association.
  void Merge(int from, int into, const PolarLine& into_line);

  int size() const { return static_cast<int>(entries_.size()); }
  int Block(int landmark) const { return entries_[landmark].block; }
  const LineExtent& Extent(int landmark) const { return entries_[landmark].extent; }
  // The landmark `landmark` was merged into, or -1 while it is a landmark of its own.
  int MergedInto(int landmark) const { return entries_[landmark].merged_into; }
  bool Active(int landmark) const { return entries_[landmark].merged_into < 0; }

 private:
  struct Entry {
    int block;
    LineExtent extent;
    int merged_into = -1;
  };
  std::vector<Entry> entries_;
};

// SPEC S1 (line association): each sighting of a scan (robot frame) against the line landmarks
// of `map`, seen from pose block `pose_block`. Individual compatibility is the Mahalanobis
// distance of (ρ, α) under `model` with a χ² gate, among the landmarks that pass the model's gate
// and whose extent the sighting's world segment overlaps within overlap_margin_m; the nearest
// compatible one is taken. A landmark takes at most one sighting per scan (a second compatible
// sighting is dropped). A sighting with no overlapping landmark within new_landmark_chi2 is new
// if it is at least min_new_length_m long, its ρ passes the model's min_rho_m and it is separated
// from every overlapping landmark by new_min_separation_* (else dropped).
class LineAssociator {
 public:
  explicit LineAssociator(const LineAssociationParams& params = {}) : params_(params) {}

  // One decision per sighting, in order; kNew decisions carry landmark -1.
  std::vector<AssociationDecision> Associate(const BlockEkf& ekf, int pose_block,
                                             const LineLandmarkModel& model, const LineMap& map,
                                             std::span<const LineSegment> sightings) const;
  const LineAssociationParams& params() const { return params_; }

 private:
  // The nearest active, gated, overlapping landmark and whether the sighting is separated from
  // all of those (new_min_separation_*).
  struct Nearest {
    int landmark = -1;
    double distance_chi2 = std::numeric_limits<double>::infinity();
    bool separated = true;
  };
  Nearest NearestOverlapping(const BlockEkf& ekf, int pose_block, const LineLandmarkModel& model,
                             const LineMap& map, const LineSegment& sighting) const;
  AssociationDecision Decide(const BlockEkf& ekf, int pose_block, const LineLandmarkModel& model,
                             const LineMap& map, const LineSegment& sighting,
                             const std::vector<char>& taken) const;

  LineAssociationParams params_;
};

}  // namespace slamkit
