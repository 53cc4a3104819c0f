#include "slamkit/filters/selection.hpp"

#include <stdexcept>

namespace slamkit {

BlockSelectionSession::BlockSelectionSession(BlockEkf& ekf,
                                             std::vector<MatchedObservation> observations)
    : ekf_(&ekf), observations_(std::move(observations)), applied_(observations_.size(), 0) {}

Linearisation BlockSelectionSession::Linearised(int i) const {
  const MatchedObservation& o = observations_[i];
  return Linearise(*o.model, *ekf_, o.block_view(), o.z, o.R);
}

void BlockSelectionSession::Apply(int i) {
  if (applied_[i]) throw std::logic_error("SelectionSession::Apply: observation applied twice");
  applied_[i] = 1;
  ekf_->Update(Linearised(i));
}

}  // namespace slamkit
