#pragma once

#include "slamkit/filters/selection/selection.hpp"

namespace slamkit {

// SPEC S1 item 3, Algorithm 3. The seed gives no value for its budget; 3 is ours (with about 10
// matched lines and corners a step, a third of the sequential update's cost).
struct CovarianceSelectionParams {
  int k_max = 3;  // most observations applied per step; >= 0
};

// Covariance-sensitivity selection (SPEC S1 item 3, Algorithm 3): greedily the unapplied
// observation with the largest |S_i| / |R_i| (the largest shrink of |P|), applied, then the
// sensitivities of the rest asked again from the updated posterior; at most k_max per step. With
// no more than k_max matched, all are applied in scan order (the sequential EKF, SelectAll).
// O(1) in the state size per candidate (only the small S block), so the step costs k_max O(n²).
class SelectByCovariance final : public SelectionPolicy {
 public:
  // Throws std::invalid_argument if k_max < 0.
  explicit SelectByCovariance(const CovarianceSelectionParams& params = {});
  void Select(SelectionSession& session) override;

 private:
  CovarianceSelectionParams params_;
};

// SPEC S1 item 2 (Zhang et al. 2005). The seed gives no value for δ; ours keeps an observation
// whose update removes more than 0.1 nats of entropy, i.e. |S| / |R| > e^0.2 ≈ 1.22 (on the
// simulated landmark circuit of the tests, with 10 cm / 1° range-bearing sightings, it keeps
// about 80 % of them; 0.2 keeps about 30 %).
struct EntropySelectionParams {
  double min_gain_nats = 0.1;  // δ, finite
};

// Entropy selection as the seed specifies it (SPEC S1 item 2, Algorithm 2): in scan order, the
// information gain ΔI = ½ (ln|P⁻| − ln|P⁺|) of each matched observation from dense Cholesky
// log-determinants of the FULL covariance before and after its tentative update; applied only if
// ΔI > δ. O(n³) per observation by design: that cost is what the seed compares against. Where the
// covariance is singular (no log-determinant) the gain is taken from Sylvester's identity.
class SelectByEntropy final : public SelectionPolicy {
 public:
  // Throws std::invalid_argument if min_gain_nats is not finite.
  explicit SelectByEntropy(const EntropySelectionParams& params = {});
  void Select(SelectionSession& session) override;

 private:
  EntropySelectionParams params_;
};

// The same decisions as SelectByEntropy at O(1) per observation: ΔI = ½ (ln|S_i| − ln|R_i|) by
// Sylvester's identity |P⁺| / |P⁻| = |R_i| / |S_i| (SPEC S1 item 3). Not the seed's baseline.
class SelectByEntropyFast final : public SelectionPolicy {
 public:
  // Throws std::invalid_argument if min_gain_nats is not finite.
  explicit SelectByEntropyFast(const EntropySelectionParams& params = {});
  void Select(SelectionSession& session) override;

 private:
  EntropySelectionParams params_;
};

// ΔI of observation i against the session's current posterior, in nats: dense (O(n³), SPEC S1
// item 2) and through Sylvester's identity (O(1)).
double DenseInformationGain(const SelectionSession& session, int i);
double FastInformationGain(const SelectionSession& session, int i);

}  // namespace slamkit
