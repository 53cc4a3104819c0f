#include "slamkit/filters/data_association.hpp"

#include <limits>
#include <vector>

namespace slamkit {

// SPEC S2, Eqs. 6-7.
AssociationDecision NearestNeighbourAssociator::Associate(
    std::span<const AssociationCandidate> candidates) const {
  AssociationDecision best;
  best.distance_chi2 = std::numeric_limits<double>::infinity();
  for (const AssociationCandidate& c : candidates) {
    if (c.distance_chi2 < best.distance_chi2) {
      best.distance_chi2 = c.distance_chi2;
      best.landmark = c.landmark;
    }
  }
  if (best.distance_chi2 < params_.gate_chi2) {
    best.kind = AssociationDecision::Kind::kMatched;
  } else if (best.distance_chi2 >= params_.new_landmark_chi2) {
    best.kind = AssociationDecision::Kind::kNew;
    best.landmark = -1;
  } else {
    best.kind = AssociationDecision::Kind::kDropped;
    best.landmark = -1;
  }
  return best;
}

// A landmark taken by an earlier observation of the scan is no candidate for the later ones: two
// sightings in one scan are two landmarks.
std::vector<AssociationDecision> NearestNeighbourAssociator::Associate(
    const AssociationContext& scan) {
  std::vector<AssociationDecision> decisions;
  decisions.reserve(scan.NumObservations());
  taken_.assign(scan.NumLandmarks(), 0);
  for (int i = 0; i < scan.NumObservations(); ++i) {
    free_.clear();
    for (const AssociationCandidate& c : scan.Candidates(i)) {
      if (!taken_[c.landmark]) free_.push_back(c);
    }
    const AssociationDecision d = Associate(free_);
    if (d.kind == AssociationDecision::Kind::kMatched) taken_[d.landmark] = 1;
    decisions.push_back(d);
  }
  return decisions;
}

std::vector<AssociationDecision> KnownAssociation::Associate(const AssociationContext& scan) {
  std::vector<AssociationDecision> decisions(scan.NumObservations());
  for (int i = 0; i < scan.NumObservations(); ++i) {
    AssociationDecision& d = decisions[i];
    const int landmark = scan.LandmarkWithSourceId(scan.Observation(i).id);
    if (landmark < 0) {
      d.kind = AssociationDecision::Kind::kNew;
      d.distance_chi2 = std::numeric_limits<double>::infinity();
    } else {
      d.kind = AssociationDecision::Kind::kMatched;
      d.landmark = landmark;
      d.distance_chi2 = scan.Distance(i, landmark);
    }
  }
  return decisions;
}

}  // namespace slamkit
