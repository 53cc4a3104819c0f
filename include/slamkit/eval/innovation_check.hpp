#pragma once

#include <string>

namespace slamkit {

// Whether a run's sightings fit its noise model, from its association outcome and the log's own
// landmark ids. A re-observation of a mapped landmark falls outside the association gate with the
// gate's χ² tail probability (1 % for a 99 % gate) when the noise model is right; when the noise
// is too small, the filter's innovations are larger than its covariance says, re-observations
// miss their landmarks' gates and start duplicates or are dropped. The log's ids count the
// landmarks that are truly new, so the rest of the misses are re-observations.
//
// The mean normalised innovation of the matched sightings cannot show this: the gate cuts off
// exactly the innovations that are too large (Victoria Park with the file's own noise averages
// 0.41 against 1.91 expected, as low as with a well-tuned config).
struct InnovationCheckParams {
  // Re-observations outside the gate more than this many times the gate's tail probability are
  // "far outside their band". The binomial band itself is a fraction of a per cent wide over a
  // log's thousands of sightings, and real sightings are not Gaussian, so a usable run may sit
  // off it; twice the tail is far. On Victoria Park (docs/victoria_park.md) the tuned config
  // sits at 0.26 times, the file's own noise at 15 times, and a run 38 m off its reference at 3.
  double max_ratio = 2.0;
  int min_reobservations = 100;  // fewer: no verdict
};

enum class InnovationVerdict {
  kTooFew,         // under min_reobservations re-observations, or no ids in the log
  kConsistent,     // re-observations miss their gates about as often as the gate allows
  kNoiseTooSmall,  // far more often: the filter is overconfident
};

struct InnovationCheck {
  long sightings = 0;
  long outside_gate = 0;         // started a landmark or dropped: matched none
  long reference_landmarks = 0;  // distinct ids of the log: the sightings that are truly new
  double reobservations_outside_share = 0.0;  // (outside_gate − reference) / (sightings − reference)
  double expected_share = 0.0;   // the gate's χ² tail probability
  double band_hi = 0.0;          // 95 % upper bound of that share over the re-observations
  double ratio = 0.0;            // reobservations_outside_share / expected_share
  InnovationVerdict verdict = InnovationVerdict::kTooFew;
  bool warn() const { return verdict == InnovationVerdict::kNoiseTooSmall; }
};

// The check of a run with `sightings` sightings of which `outside_gate` matched no landmark, on
// a log naming `reference_landmarks` distinct landmarks, gated at `gate_chi2` with `dof`.
InnovationCheck CheckInnovations(long sightings, long outside_gate, long reference_landmarks,
                                 int dof, double gate_chi2, const InnovationCheckParams& params = {});

// "consistent", "noise_too_small" or "too_few".
std::string VerdictName(InnovationVerdict verdict);

}  // namespace slamkit
