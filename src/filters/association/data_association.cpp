#include "slamkit/filters/association/data_association.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include <Eigen/LU>

namespace slamkit {

// SPEC S2, Eqs. 6-7.
AssociationDecision NearestNeighbourAssociator::Associate(
    std::span<const AssociationCandidate> candidates) const {
  AssociationDecision best;
  best.distance_chi2 = std::numeric_limits<double>::infinity();
  for (const AssociationCandidate& c : candidates) {
    if (c.distance_chi2 < best.distance_chi2) {
      best.distance_chi2 = c.distance_chi2;
      best.landmark = c.landmark;
    }
  }
  if (best.distance_chi2 < params_.gate_chi2) {
    best.kind = AssociationDecision::Kind::kMatched;
  } else if (best.distance_chi2 >= params_.new_landmark_chi2) {
    best.kind = AssociationDecision::Kind::kNew;
    best.landmark = -1;
  } else {
    best.kind = AssociationDecision::Kind::kDropped;
    best.landmark = -1;
  }
  return best;
}

namespace {

// A landmark taken by an earlier observation of the scan is no candidate for the later ones: two
// sightings in one scan are two landmarks. `rule(i, free)` decides observation i.
template <class Rule>
std::vector<AssociationDecision> DecideInScanOrder(const AssociationContext& scan,
                                                   std::vector<AssociationCandidate>& free,
                                                   std::vector<char>& taken, Rule rule) {
  std::vector<AssociationDecision> decisions;
  decisions.reserve(scan.NumObservations());
  taken.assign(scan.NumLandmarks(), 0);
  for (int i = 0; i < scan.NumObservations(); ++i) {
    free.clear();
    for (const AssociationCandidate& c : scan.Candidates(i)) {
      if (!taken[c.landmark]) free.push_back(c);
    }
    const AssociationDecision d = rule(i, std::span<const AssociationCandidate>(free));
    if (d.kind == AssociationDecision::Kind::kMatched) taken[d.landmark] = 1;
    decisions.push_back(d);
  }
  return decisions;
}

// -2 ln N(ν; 0, S) less the constant 2 ln 2π: what maximum likelihood minimises.
double NegativeLogDensity(const AssociationContext& scan, int observation,
                          const AssociationCandidate& c) {
  const Pairing pairing{observation, c.landmark};
  const JointInnovation joint = scan.Joint(std::span<const Pairing>(&pairing, 1));
  return c.distance_chi2 + std::log(joint.S.determinant());
}

}  // namespace

std::vector<AssociationDecision> NearestNeighbourAssociator::Associate(
    const AssociationContext& scan) {
  return DecideInScanOrder(scan, free_, taken_,
                           [this](int, std::span<const AssociationCandidate> free) {
                             return Associate(free);
                           });
}

std::vector<AssociationDecision> MaximumLikelihoodAssociator::Associate(
    const AssociationContext& scan) {
  const double gate = nearest_.params().gate_chi2;
  return DecideInScanOrder(
      scan, free_, taken_, [&](int i, std::span<const AssociationCandidate> free) {
        AssociationDecision d = nearest_.Associate(free);
        if (d.kind != AssociationDecision::Kind::kMatched) return d;
        double best = std::numeric_limits<double>::infinity();
        for (const AssociationCandidate& c : free) {
          if (c.distance_chi2 >= gate) continue;
          const double cost = NegativeLogDensity(scan, i, c);
          if (cost < best) {
            best = cost;
            d.landmark = c.landmark;
            d.distance_chi2 = c.distance_chi2;
          }
        }
        return d;
      });
}

std::vector<AssociationDecision> GlobalNearestNeighbourAssociator::Associate(
    const AssociationContext& scan) {
  const int n = scan.NumObservations();
  std::vector<AssociationDecision> decisions(static_cast<std::size_t>(n));
  pairs_.clear();
  for (int i = 0; i < n; ++i) {
    decisions[i].distance_chi2 = std::numeric_limits<double>::infinity();
    for (const AssociationCandidate& c : scan.Candidates(i)) {
      decisions[i].distance_chi2 = std::min(decisions[i].distance_chi2, c.distance_chi2);
      if (c.distance_chi2 < params_.gate_chi2) pairs_.push_back({c.distance_chi2, i, c.landmark});
    }
  }
  // Stable: equal distances keep observation, then landmark order.
  std::stable_sort(pairs_.begin(), pairs_.end(), [](const GatedPair& a, const GatedPair& b) {
    return a.distance_chi2 < b.distance_chi2;
  });
  std::vector<char> taken(static_cast<std::size_t>(scan.NumLandmarks()), 0);
  for (const GatedPair& p : pairs_) {
    AssociationDecision& d = decisions[p.observation];
    if (d.kind == AssociationDecision::Kind::kMatched || taken[p.landmark]) continue;
    d = {AssociationDecision::Kind::kMatched, p.landmark, p.distance_chi2};
    taken[p.landmark] = 1;
  }
  for (AssociationDecision& d : decisions) {
    if (d.kind == AssociationDecision::Kind::kMatched) continue;
    d.kind = d.distance_chi2 >= params_.new_landmark_chi2 ? AssociationDecision::Kind::kNew
                                                           : AssociationDecision::Kind::kDropped;
  }
  return decisions;
}

std::vector<AssociationDecision> KnownAssociation::Associate(const AssociationContext& scan) {
  std::vector<AssociationDecision> decisions(scan.NumObservations());
  for (int i = 0; i < scan.NumObservations(); ++i) {
    AssociationDecision& d = decisions[i];
    const int landmark = scan.LandmarkWithSourceId(scan.Observation(i).id);
    if (landmark < 0) {
      d.kind = AssociationDecision::Kind::kNew;
      d.distance_chi2 = std::numeric_limits<double>::infinity();
    } else {
      d.distance_chi2 = scan.Distance(i, landmark);
      const bool inlier = !(d.distance_chi2 > gate_chi2_);  // NaN: kept, as before the gate
      d.kind = inlier ? AssociationDecision::Kind::kMatched : AssociationDecision::Kind::kDropped;
      d.landmark = inlier ? landmark : -1;
    }
  }
  return decisions;
}

}  // namespace slamkit
