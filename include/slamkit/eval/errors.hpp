#pragma once

#include <map>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/ids.hpp"

namespace slamkit {

// Normalised estimation error squared eᵀ C⁻¹ e of a pose error (dx, dy, wrapped dθ). When C is
// singular or indefinite (an eigenvalue at most 1e-14 of the largest), the error along those
// directions decides: none (|e| ≤ 1e-12 there, as at a filter's exact start) adds nothing, any
// other is +infinity: a filter that claims to know a direction exactly and is wrong there is
// infinitely over-confident. A particle filter whose particles collapsed onto one pose does that.
double Nees(const Eigen::Vector3d& error, const Eigen::Matrix3d& covariance);

// Root mean square of the position part and of the heading part of pose errors.
struct PoseRmse {
  double position_m = 0.0;
  double heading_rad = 0.0;
};
PoseRmse ComputePoseRmse(std::span<const Eigen::Vector3d> errors);

// How a filter's association did against the truth, joined after the run (the filter never sees
// the true ids). A sighting is matchable when its true landmark was already in the map; a match
// is correct when the landmark it matched was created from a sighting of the same true landmark.
struct AssociationScore {
  int sightings = 0;
  int matched = 0;
  int correct = 0;
  int matchable = 0;
  int created = 0;
  int dropped = 0;
  double Precision() const { return matched > 0 ? double(correct) / matched : 1.0; }
  double Recall() const { return matchable > 0 ? double(correct) / matchable : 1.0; }
};

// What a filter did with one sighting (the filters' AssociationDecision::Kind, seen from here).
enum class AssociationOutcome { kMatched, kNew, kDropped };

// Accumulates AssociationScore one decision at a time, in filter order, from plain data.
class AssociationScorer {
 public:
  // `true_id` is the sighting's true landmark, `outcome` what the filter did with it and
  // `matched_true_id` the true id of the landmark it was matched to (ignored unless the outcome
  // is a match). A landmark's true id is the caller's to decide: the harness takes that of the
  // sighting that created it.
  void Add(LandmarkId true_id, AssociationOutcome outcome, LandmarkId matched_true_id);
  const AssociationScore& score() const { return score_; }

 private:
  AssociationScore score_;
  std::vector<LandmarkId> mapped_ids_;  // sorted
};

// One-to-one matching of a filter's landmarks to a reference's ids (a data set's), greedily by
// the number of sightings they share (largest first); the agreement is the share of all
// `sightings` that fall on matched pairs. A reference landmark split into two of ours, or two
// merged into one, loses the smaller part. `assigned` holds (our landmark index, the
// reference's id) per sighting; an index below 0 (not mapped) agrees with nothing.
struct IdAgreement {
  double share = 0.0;
  std::map<int, LandmarkId> pairs;  // our landmark index → the reference id it was matched to
};
IdAgreement AssociationAgreement(const std::vector<std::pair<int, LandmarkId>>& assigned,
                                 int sightings);

}  // namespace slamkit
