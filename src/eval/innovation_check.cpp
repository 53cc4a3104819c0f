#include "slamkit/eval/innovation_check.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <boost/math/distributions/chi_squared.hpp>

namespace slamkit {

InnovationCheck CheckInnovations(long sightings, long outside_gate, long reference_landmarks,
                                 int dof, double gate_chi2, const InnovationCheckParams& params) {
  if (dof <= 0 || !(gate_chi2 > 0.0) || !(params.max_ratio > 1.0) || sightings < 0 ||
      outside_gate < 0 || outside_gate > sightings || reference_landmarks < 0) {
    throw std::invalid_argument("CheckInnovations: dof and gate must be positive, max_ratio above "
                                "1, and 0 <= outside_gate <= sightings");
  }
  InnovationCheck out;
  out.sightings = sightings;
  out.outside_gate = outside_gate;
  out.reference_landmarks = reference_landmarks;
  out.expected_share = boost::math::cdf(
      boost::math::complement(boost::math::chi_squared_distribution<double>(dof), gate_chi2));
  const long reobservations = sightings - reference_landmarks;
  if (reference_landmarks == 0 || reobservations < params.min_reobservations) return out;
  const double n = static_cast<double>(reobservations);
  // A landmark's first sighting is outside every gate; more misses than ids leaves a share < 0
  // only when landmarks were merged, which this check does not judge.
  out.reobservations_outside_share =
      std::max(0.0, static_cast<double>(outside_gate - reference_landmarks) / n);
  const double p = out.expected_share;
  out.band_hi = p + 1.96 * std::sqrt(p * (1.0 - p) / n);
  out.ratio = out.reobservations_outside_share / p;
  out.verdict = out.ratio > params.max_ratio ? InnovationVerdict::kNoiseTooSmall
                                             : InnovationVerdict::kConsistent;
  return out;
}

std::string VerdictName(InnovationVerdict verdict) {
  switch (verdict) {
    case InnovationVerdict::kTooFew: return "too_few";
    case InnovationVerdict::kConsistent: return "consistent";
    case InnovationVerdict::kNoiseTooSmall: return "noise_too_small";
  }
  return "too_few";
}

}  // namespace slamkit
