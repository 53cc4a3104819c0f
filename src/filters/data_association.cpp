#include "slamkit/filters/data_association.hpp"

#include <limits>

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

}  // namespace slamkit
