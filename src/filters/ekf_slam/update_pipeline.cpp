#include "slamkit/filters/ekf_slam/update_pipeline.hpp"

#include <utility>

namespace slamkit {

UpdatePipeline::UpdatePipeline(BlockEkf& ekf, int observer,
                               std::span<LandmarkSightings* const> kinds)
    : ekf_(&ekf), observer_(observer), kinds_(kinds), decisions_(kinds.size()) {}

// SPEC S2, Eqs. 6-7 (SPEC S1 for lines): every kind against the prior, before any update, so
// that a policy ranking the scan sees all of it (SPEC S1 item 3).
void UpdatePipeline::Associate() {
  for (std::size_t k = 0; k < kinds_.size(); ++k) {
    decisions_[k] = kinds_[k]->Associate(*ekf_, observer_);
  }
}

std::vector<MatchedObservation> UpdatePipeline::Matched() const {
  std::vector<MatchedObservation> matched;
  for (std::size_t k = 0; k < kinds_.size(); ++k) {
    const std::vector<AssociationDecision>& decided = decisions_[k];
    for (std::size_t i = 0; i < decided.size(); ++i) {
      if (decided[i].kind != AssociationDecision::Kind::kMatched) continue;
      matched.push_back(kinds_[k]->Matched(observer_, static_cast<int>(i), decided[i].landmark));
    }
  }
  return matched;
}

// SPEC S1 items 1 and 3: the policy chooses among the matched sightings of all kinds from their
// S, H and R against the current posterior; each applied one is a sequential update (Table 10.2
// of Probabilistic Robotics).
SelectionStats UpdatePipeline::SelectAndUpdate(SelectionPolicy& policy, bool diagnostics) {
  std::vector<MatchedObservation> matched = Matched();
  if (matched.empty()) return {};
  BlockSelectionSession session(*ekf_, std::move(matched), diagnostics);
  policy.Select(session);
  return session.stats();
}

// SPEC S2, Eq. 8, kind by kind, each kind's new sightings in scan order.
void UpdatePipeline::Augment() {
  for (std::size_t k = 0; k < kinds_.size(); ++k) {
    std::vector<AssociationDecision>& decided = decisions_[k];
    for (std::size_t i = 0; i < decided.size(); ++i) {
      if (decided[i].kind != AssociationDecision::Kind::kNew) continue;
      decided[i].landmark = kinds_[k]->Augment(*ekf_, observer_, static_cast<int>(i));
    }
  }
}

SelectionStats UpdatePipeline::Run(SelectionPolicy& policy, bool diagnostics) {
  Associate();
  const SelectionStats stats = SelectAndUpdate(policy, diagnostics);
  Augment();
  return stats;
}

}  // namespace slamkit
