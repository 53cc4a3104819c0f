#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf/observation_model.hpp"

namespace slamkit {

// ln|A| of a symmetric positive-definite matrix by Cholesky (2 Σ ln L_ii); -∞ if the
// factorisation fails (A singular or indefinite).
template <typename Matrix>
double LogDetPositiveDefinite(const Matrix& A) {
  const Eigen::LLT<typename Matrix::PlainObject> llt(A);
  if (llt.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
  return 2.0 * llt.matrixLLT().diagonal().array().log().sum();
}

// The matched observations of one step, offered to a selection policy. S(i), H(i) and R(i) are
// those of observation i linearised at the current posterior: after each Apply() they change, so
// a policy that ranks by them (SPEC S1 item 3, Algorithm 3) re-ranks simply by asking again.
class SelectionSession {
 public:
  virtual ~SelectionSession() = default;

  virtual int size() const = 0;
  virtual BlockMatrix S(int i) const = 0;
  virtual BlockJacobians H(int i) const = 0;
  virtual BlockMatrix R(int i) const = 0;
  virtual bool applied(int i) const = 0;
  // The sequential EKF update with observation i, linearised now; once per observation.
  virtual void Apply(int i) = 0;

  // ln|P| of the full current covariance, by a dense Cholesky: O(n³). -∞ if P is singular.
  // SPEC S1 item 2 (the entropy policy needs it; the cost is the seed's point of comparison).
  virtual double LogDetCovariance() const = 0;
  // ln|P⁺| of the full covariance after observation i's tentative update, P⁺ = P − P Hᵀ S⁻¹ H P,
  // without applying it: O(n³). -∞ if P⁺ is singular.
  virtual double LogDetAfter(int i) const = 0;
};

// ln|S_i| − ln|R_i| = ln|P⁻| − ln|P⁺| of observation i's update (Sylvester's identity,
// SPEC S1 item 3): the covariance sensitivity, O(1) in the state size.
double LogSensitivity(const SelectionSession& session, int i);

// Chooses which matched observations update the filter and in what order.
class SelectionPolicy {
 public:
  virtual ~SelectionPolicy() = default;
  virtual void Select(SelectionSession& session) = 0;
};

// Every matched observation, in scan order: the plain sequential EKF.
class SelectAll final : public SelectionPolicy {
 public:
  void Select(SelectionSession& session) override {
    for (int i = 0; i < session.size(); ++i) session.Apply(i);
  }
};

// What one selection step did, recorded by the session (SPEC S1 item 3 and Eq. 24). Log-ratios
// are in nats and never positive: an update only shrinks the uncertainty volume.
struct SelectionStats {
  int candidates = 0;  // matched observations offered to the policy
  int applied = 0;     // of them, applied
  // Σ over the applied updates of ln(|R_i| / |S_i|), each S_i taken when it was applied:
  // ln|P⁺| − ln|P⁻| of the whole correction.
  double selected_log_ratio = 0.0;
  // With diagnostics on: the same sum for the full sequential update of every candidate, in scan
  // order, from the same prior (evaluated on the marginal of the blocks they touch).
  std::optional<double> all_log_ratio;

  // SPEC S1, Eq. 24: the share of the full update's log-determinant reduction that the
  // selection kept. Needs diagnostics; none for a step with nothing to reduce.
  std::optional<double> accuracy() const {
    if (!all_log_ratio || *all_log_ratio == 0.0) return std::nullopt;
    return selected_log_ratio / *all_log_ratio;
  }
  // Accumulates another part of the same step (the per-observation schedule runs one each).
  void Add(const SelectionStats& part);
};

// One matched observation: its model, the blocks it involves and the measurement.
struct MatchedObservation {
  const ObservationModel* model = nullptr;
  std::array<int, kMaxObservedBlocks> blocks{};
  int num_blocks = 0;
  BlockVector z;
  BlockMatrix R;

  std::span<const int> block_view() const { return {blocks.data(), std::size_t(num_blocks)}; }
};

// A SelectionSession on a BlockEkf: linearises on demand, so SelectAll costs nothing beyond the
// updates themselves, and again after every applied update. Updates stay deferred; the dense
// log-determinants read the covariance through the pending downdate without applying it.
class BlockSelectionSession final : public SelectionSession {
 public:
  // With `diagnostics`, the full sequential update of all `observations` is run first on the
  // marginal of the blocks they touch (BlockEkf::Marginal, O(k²) in their k entries) to fill
  // stats().all_log_ratio.
  BlockSelectionSession(BlockEkf& ekf, std::vector<MatchedObservation> observations,
                        bool diagnostics = false);

  int size() const override { return static_cast<int>(observations_.size()); }
  BlockMatrix S(int i) const override { return ekf_->InnovationCovariance(Linearised(i)); }
  BlockJacobians H(int i) const override { return Linearised(i).H; }
  BlockMatrix R(int i) const override { return observations_[i].R; }
  bool applied(int i) const override { return applied_[i] != 0; }
  void Apply(int i) override;
  double LogDetCovariance() const override;
  double LogDetAfter(int i) const override;

  const SelectionStats& stats() const { return stats_; }

 private:
  Linearisation Linearised(int i) const;

  BlockEkf* ekf_;
  std::vector<MatchedObservation> observations_;
  std::vector<char> applied_;
  SelectionStats stats_;
};

}  // namespace slamkit
