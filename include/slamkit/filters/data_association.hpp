#pragma once

#include <span>

namespace slamkit {

struct AssociationParams {
  // Squared Mahalanobis distance under which an observation matches a landmark
  // (χ²₂ at 99 %: 9.21).
  double gate_chi2 = 9.21;
  // Above this distance to every landmark an observation starts a new landmark (χ²₂ at 99.9 %:
  // 13.82); between the two gates it is ambiguous and dropped.
  double new_landmark_chi2 = 13.82;
};

// A landmark the filter considered for an observation, with its squared Mahalanobis distance
// νᵀ S⁻¹ ν (SPEC S2, Eqs. 6-7).
struct AssociationCandidate {
  int landmark = -1;
  double distance_chi2 = 0.0;
};

struct AssociationDecision {
  enum class Kind { kMatched, kNew, kDropped };
  Kind kind = Kind::kDropped;
  int landmark = -1;          // the matched or created landmark's index, -1 when dropped
  double distance_chi2 = 0.0; // to the nearest candidate (infinity when there was none)
};

// SPEC S2, Eqs. 6-7: nearest neighbour on the Mahalanobis distance with a χ² gate, and a second,
// larger gate that separates new landmarks from ambiguous sightings.
class NearestNeighbourAssociator {
 public:
  explicit NearestNeighbourAssociator(const AssociationParams& params = {}) : params_(params) {}
  // Decides from the candidates; a kNew decision carries landmark -1 (the filter assigns it).
  AssociationDecision Associate(std::span<const AssociationCandidate> candidates) const;
  const AssociationParams& params() const { return params_; }

 private:
  AssociationParams params_;
};

}  // namespace slamkit
