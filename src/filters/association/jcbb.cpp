#include "slamkit/filters/association/jcbb.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <boost/math/distributions/chi_squared.hpp>

namespace slamkit {

// One Associate()'s interpretation tree: per observation its individually compatible landmarks
// (nearest first), the branch being explored and the best hypothesis so far.
struct JcbbAssociator::Search {
  std::vector<std::vector<AssociationCandidate>> compatible;
  std::vector<double> nearest_chi2;  // over all candidates, for the new-landmark rule
  std::vector<int> pairable_after;   // observations after i with a compatible landmark
  std::vector<Pairing> branch;
  std::vector<double> branch_d2;  // the joint D² of branch[0..k]
  std::vector<char> used;         // landmarks in the branch
  std::vector<Pairing> best;
  double best_d2 = std::numeric_limits<double>::infinity();
};

JcbbAssociator::JcbbAssociator(const AssociationParams& individual, const JcbbParams& joint)
    : individual_(individual), params_(joint) {
  if (!(joint.joint_probability > 0.0 && joint.joint_probability < 1.0)) {
    throw std::invalid_argument("JcbbParams: joint_probability must be in (0, 1)");
  }
  if (joint.max_joint_tests < 0) {
    throw std::invalid_argument("JcbbParams: max_joint_tests must be >= 0");
  }
}

double JcbbAssociator::JointGate(int pairings, int dim) {
  const int dof = pairings * dim;
  if (static_cast<int>(gates_.size()) <= dof) gates_.resize(dof + 1, -1.0);
  if (gates_[dof] < 0.0) {
    gates_[dof] = boost::math::quantile(boost::math::chi_squared(dof), params_.joint_probability);
  }
  return gates_[dof];
}

// Neira & Tardós 2001, Eq. 9: D² = νᵀ S⁻¹ ν of the stacked innovations of the branch.
bool JcbbAssociator::JointlyCompatible(const AssociationContext& scan, Search& s) {
  ++tests_;
  const JointInnovation joint = scan.Joint(s.branch);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(joint.S);
  if (ldlt.info() != Eigen::Success) return false;
  const double d2 = joint.nu.dot(ldlt.solve(joint.nu));
  const int pairings = static_cast<int>(s.branch.size());
  if (!(d2 < JointGate(pairings, static_cast<int>(joint.nu.size()) / pairings))) return false;
  s.branch_d2.push_back(d2);
  return true;
}

// Neira & Tardós 2001, Table 1 (JCBB): observation i paired with each free compatible landmark
// whose addition keeps the branch jointly compatible, then left unpaired if the observations
// after it could still make the branch beat the best.
void JcbbAssociator::Branch(const AssociationContext& scan, Search& s, int i) {
  const int m = static_cast<int>(s.compatible.size());
  if (i == m) {
    const double d2 = s.branch_d2.empty() ? 0.0 : s.branch_d2.back();
    if (s.branch.size() > s.best.size() || (s.branch.size() == s.best.size() && d2 < s.best_d2)) {
      s.best = s.branch;
      s.best_d2 = d2;
    }
    return;
  }
  for (const AssociationCandidate& c : s.compatible[i]) {
    if (s.used[c.landmark]) continue;
    if (tests_ >= params_.max_joint_tests) {
      truncated_ = true;
      break;
    }
    s.branch.push_back({i, c.landmark});
    if (JointlyCompatible(scan, s)) {
      s.used[c.landmark] = 1;
      Branch(scan, s, i + 1);
      s.used[c.landmark] = 0;
      s.branch_d2.pop_back();
    }
    s.branch.pop_back();
  }
  if (s.branch.size() + s.pairable_after[i] > s.best.size()) Branch(scan, s, i + 1);
}

std::vector<AssociationDecision> JcbbAssociator::Associate(const AssociationContext& scan) {
  const int m = scan.NumObservations();
  tests_ = 0;
  truncated_ = false;
  Search s;
  s.compatible.resize(m);
  s.nearest_chi2.assign(m, std::numeric_limits<double>::infinity());
  for (int i = 0; i < m; ++i) {
    for (const AssociationCandidate& c : scan.Candidates(i)) {  // a scratch span: copy now
      s.nearest_chi2[i] = std::min(s.nearest_chi2[i], c.distance_chi2);
      if (c.distance_chi2 < individual_.gate_chi2) s.compatible[i].push_back(c);
    }
    std::sort(s.compatible[i].begin(), s.compatible[i].end(),
              [](const auto& a, const auto& b) { return a.distance_chi2 < b.distance_chi2; });
  }
  s.pairable_after.assign(m, 0);
  for (int i = m - 2; i >= 0; --i) {
    s.pairable_after[i] = s.pairable_after[i + 1] + (s.compatible[i + 1].empty() ? 0 : 1);
  }
  s.used.assign(scan.NumLandmarks(), 0);
  Branch(scan, s, 0);

  std::vector<AssociationDecision> decisions(m);
  for (int i = 0; i < m; ++i) {
    AssociationDecision& d = decisions[i];
    d.distance_chi2 = s.nearest_chi2[i];
    d.kind = s.nearest_chi2[i] >= individual_.new_landmark_chi2
                 ? AssociationDecision::Kind::kNew
                 : AssociationDecision::Kind::kDropped;
  }
  for (const Pairing& p : s.best) {
    AssociationDecision& d = decisions[p.observation];
    d.kind = AssociationDecision::Kind::kMatched;
    d.landmark = p.landmark;
    d.distance_chi2 = scan.Distance(p.observation, p.landmark);
  }
  return decisions;
}

}  // namespace slamkit
