#include "slamkit/filters/selection/selection_policies.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace slamkit {
namespace {

void CheckGainThreshold(const EntropySelectionParams& params) {
  if (!std::isfinite(params.min_gain_nats)) {
    throw std::invalid_argument("EntropySelectionParams: min_gain_nats must be finite");
  }
}

}  // namespace

double DenseInformationGain(const SelectionSession& session, int i) {
  const double gain = 0.5 * (session.LogDetCovariance() - session.LogDetAfter(i));
  // A singular P has no log-determinant (−∞ − −∞): the gain on the subspace where it is not
  // singular is what Sylvester's identity gives.
  return std::isfinite(gain) ? gain : FastInformationGain(session, i);
}

double FastInformationGain(const SelectionSession& session, int i) {
  return 0.5 * LogSensitivity(session, i);
}

SelectByCovariance::SelectByCovariance(const CovarianceSelectionParams& params) : params_(params) {
  if (params_.k_max < 0) {
    throw std::invalid_argument("CovarianceSelectionParams: k_max must be >= 0");
  }
}

// SPEC S1, Algorithm 3.
void SelectByCovariance::Select(SelectionSession& session) {
  const int n = session.size();
  if (n <= params_.k_max) {
    for (int i = 0; i < n; ++i) session.Apply(i);
    return;
  }
  std::vector<double> log_det_R(n);
  for (int i = 0; i < n; ++i) log_det_R[i] = LogDetPositiveDefinite(session.R(i));
  for (int step = 0; step < params_.k_max; ++step) {
    int best = -1;
    double best_score = 0.0;
    for (int i = 0; i < n; ++i) {
      if (session.applied(i)) continue;
      // ln|S_i| − ln|R_i| against the posterior the previous choices left.
      const double score = LogDetPositiveDefinite(session.S(i)) - log_det_R[i];
      if (best < 0 || score > best_score) {
        best = i;
        best_score = score;
      }
    }
    session.Apply(best);
  }
}

SelectByEntropy::SelectByEntropy(const EntropySelectionParams& params) : params_(params) {
  CheckGainThreshold(params_);
}

// SPEC S1 item 2 (the seed's Algorithm 2).
void SelectByEntropy::Select(SelectionSession& session) {
  for (int i = 0; i < session.size(); ++i) {
    if (DenseInformationGain(session, i) > params_.min_gain_nats) session.Apply(i);
  }
}

SelectByEntropyFast::SelectByEntropyFast(const EntropySelectionParams& params) : params_(params) {
  CheckGainThreshold(params_);
}

void SelectByEntropyFast::Select(SelectionSession& session) {
  for (int i = 0; i < session.size(); ++i) {
    if (FastInformationGain(session, i) > params_.min_gain_nats) session.Apply(i);
  }
}

}  // namespace slamkit
