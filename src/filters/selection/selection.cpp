#include "slamkit/filters/selection/selection.hpp"

#include <algorithm>
#include <stdexcept>

namespace slamkit {

double LogSensitivity(const SelectionSession& session, int i) {
  return LogDetPositiveDefinite(session.S(i)) - LogDetPositiveDefinite(session.R(i));
}

void SelectionStats::Add(const SelectionStats& part) {
  candidates += part.candidates;
  applied += part.applied;
  selected_log_ratio += part.selected_log_ratio;
  if (part.all_log_ratio) all_log_ratio = all_log_ratio.value_or(0.0) + *part.all_log_ratio;
}

namespace {

// SPEC S1, Eq. 24: the denominator, the full sequential update of every observation from the
// same prior, run on the marginal of the blocks they touch (the rest of the state does not
// change what those updates do to these blocks): O(k²) in their k entries, not a copy of n².
double FullUpdateLogRatio(const BlockEkf& ekf,
                          const std::vector<MatchedObservation>& observations) {
  std::vector<int> blocks;
  for (const MatchedObservation& o : observations) {
    for (const int b : o.block_view()) {
      if (std::find(blocks.begin(), blocks.end(), b) == blocks.end()) blocks.push_back(b);
    }
  }
  BlockEkf marginal = ekf.Marginal(blocks);
  std::vector<MatchedObservation> local = observations;
  for (MatchedObservation& o : local) {
    for (int k = 0; k < o.num_blocks; ++k) {
      o.blocks[k] = int(std::find(blocks.begin(), blocks.end(), o.blocks[k]) - blocks.begin());
    }
  }
  BlockSelectionSession full(marginal, std::move(local));
  SelectAll().Select(full);
  return full.stats().selected_log_ratio;
}

}  // namespace

BlockSelectionSession::BlockSelectionSession(BlockEkf& ekf,
                                             std::vector<MatchedObservation> observations,
                                             bool diagnostics)
    : ekf_(&ekf), observations_(std::move(observations)), applied_(observations_.size(), 0) {
  stats_.candidates = size();
  if (diagnostics) stats_.all_log_ratio = FullUpdateLogRatio(ekf, observations_);
}

Linearisation BlockSelectionSession::Linearised(int i) const {
  const MatchedObservation& o = observations_[i];
  return Linearise(*o.model, *ekf_, o.block_view(), o.z, o.R);
}

void BlockSelectionSession::Apply(int i) {
  if (applied_[i]) throw std::logic_error("SelectionSession::Apply: observation applied twice");
  applied_[i] = 1;
  const Linearisation obs = Linearised(i);
  // SPEC S1 item 3: |P⁺| / |P⁻| = |R| / |S| (Sylvester), so the sum over the applied updates is
  // the log-determinant change of the correction. S is the small block: O(1) in n.
  const double log_ratio =
      LogDetPositiveDefinite(obs.R) - LogDetPositiveDefinite(ekf_->InnovationCovariance(obs));
  if (ekf_->Update(obs)) {
    ++stats_.applied;
    stats_.selected_log_ratio += log_ratio;
  }
}

// SPEC S1 item 2 (Zhang et al. 2005, as the seed specifies): the determinant of the full
// covariance, materialised through the pending downdate (O(n²·m)) and factorised (O(n³)).
double BlockSelectionSession::LogDetCovariance() const {
  return LogDetPositiveDefinite(ekf_->Covariance());
}

// The dense textbook posterior of observation i's update on a copy of the full covariance:
// P⁺ = P − V Vᵀ with V = P Hᵀ L⁻ᵀ, S = H P Hᵀ + R = L Lᵀ. O(n³) for its log-determinant.
double BlockSelectionSession::LogDetAfter(int i) const {
  const Linearisation obs = Linearised(i);
  Eigen::MatrixXd P = ekf_->Covariance();
  const int z_dim = static_cast<int>(obs.R.rows());
  Eigen::MatrixXd PHt = Eigen::MatrixXd::Zero(P.rows(), z_dim);
  for (const BlockJacobian& h : obs.H.view()) {
    PHt += P.middleCols(ekf_->BlockOffset(h.block), ekf_->BlockDim(h.block)) * h.J.transpose();
  }
  Eigen::MatrixXd S = obs.R;
  for (const BlockJacobian& h : obs.H.view()) {
    S += h.J * PHt.middleRows(ekf_->BlockOffset(h.block), ekf_->BlockDim(h.block));
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success) return -std::numeric_limits<double>::infinity();
  const Eigen::MatrixXd V = llt.matrixL().solve(PHt.transpose()).transpose();
  P.noalias() -= V * V.transpose();
  return LogDetPositiveDefinite(P);
}

}  // namespace slamkit
