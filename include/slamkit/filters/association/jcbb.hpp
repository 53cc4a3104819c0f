#pragma once

#include <vector>

#include "slamkit/filters/association/data_association.hpp"

namespace slamkit {

// The joint test and the search's budget; the individual gate and the new-landmark rule are an
// AssociationParams, as for nearest neighbour.
struct JcbbParams {
  // Joint compatibility: a hypothesis of k pairings of d-dimensional observations is accepted
  // when its joint D² = νᵀ S⁻¹ ν is under the χ²(k·d) quantile at this probability.
  double joint_probability = 0.99;
  // The search's budget: at most this many joint-compatibility tests (each O(k³) in the
  // hypothesis size); when it runs out, the best hypothesis found so far is taken. The whole
  // interpretation tree of m observations with c candidates each has (c + 1)^m nodes.
  long max_joint_tests = 20000;
};

// Joint-compatibility branch and bound (Neira & Tardós 2001): of the hypotheses pairing the
// scan's observations with distinct, individually compatible landmarks whose joint innovation
// passes the χ² test, the one with the most pairings (ties: the smallest joint D²). Unlike
// nearest neighbour it accounts for the correlation of the innovations through the common pose
// error: a whole scan seen from a shifted pose is matched as a whole, not sighting by sighting.
// A pairing is only considered when it is individually compatible (its own squared Mahalanobis
// distance under `individual.gate_chi2`: the first gate). Observations the best hypothesis leaves
// unpaired are new if their nearest individual distance is at least
// individual.new_landmark_chi2, else dropped. Needs the whole scan at once (EkfSlam's
// UpdateSchedule::kPerScan); on a single observation it is nearest neighbour.
class JcbbAssociator final : public Associator {
 public:
  explicit JcbbAssociator(const AssociationParams& individual = {}, const JcbbParams& joint = {});
  std::vector<AssociationDecision> Associate(const AssociationContext& scan) override;

  // The last Associate(): joint tests run, and whether the budget cut the search short.
  long last_joint_tests() const { return tests_; }
  bool last_search_truncated() const { return truncated_; }

 private:
  struct Search;
  void Branch(const AssociationContext& scan, Search& s, int i);
  bool JointlyCompatible(const AssociationContext& scan, Search& s);
  double JointGate(int pairings, int dim);

  AssociationParams individual_;
  JcbbParams params_;
  std::vector<double> gates_;  // χ² quantiles by stacked dimension, computed once
  long tests_ = 0;
  bool truncated_ = false;
};

}  // namespace slamkit
