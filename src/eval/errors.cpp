#include "slamkit/eval/errors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include <Eigen/Eigenvalues>

namespace slamkit {
namespace {
// An eigenvalue below this share of the largest is a direction the covariance claims to know
// exactly (rounding leaves ~1e-16 of the scale there).
constexpr double kNeesRelativeFloor = 1e-14;
// An error this small along such a direction is no error (a filter started at the true pose).
constexpr double kNeesExactError = 1e-12;
}  // namespace

double Nees(const Eigen::Vector3d& error, const Eigen::Matrix3d& covariance) {
  // LDLT would also "solve" a singular or indefinite C and return a meaningless, even negative,
  // figure. The eigenbasis separates the directions C has from those it claims to know exactly.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(covariance);
  if (eigen.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d lambda = eigen.eigenvalues();
  const Eigen::Vector3d along = eigen.eigenvectors().transpose() * error;
  const double floor = kNeesRelativeFloor * std::max(lambda.cwiseAbs().maxCoeff(), 0.0);
  double nees = 0.0;
  for (int i = 0; i < 3; ++i) {
    if (lambda[i] > floor && lambda[i] > 0.0) {
      nees += along[i] * along[i] / lambda[i];
    } else if (std::abs(along[i]) > kNeesExactError) {
      return std::numeric_limits<double>::infinity();
    }
  }
  return nees;
}

PoseRmse ComputePoseRmse(std::span<const Eigen::Vector3d> errors) {
  if (errors.empty()) return {};
  double pos = 0.0, head = 0.0;
  for (const Eigen::Vector3d& e : errors) {
    pos += e.head<2>().squaredNorm();
    head += e.z() * e.z();
  }
  const double n = static_cast<double>(errors.size());
  return {std::sqrt(pos / n), std::sqrt(head / n)};
}

void AssociationScorer::Add(LandmarkId true_id, AssociationOutcome outcome,
                            LandmarkId matched_true_id) {
  ++score_.sightings;
  const bool in_map = std::binary_search(mapped_ids_.begin(), mapped_ids_.end(), true_id);
  if (in_map) ++score_.matchable;
  switch (outcome) {
    case AssociationOutcome::kMatched:
      ++score_.matched;
      if (matched_true_id == true_id) ++score_.correct;
      break;
    case AssociationOutcome::kNew:
      ++score_.created;
      if (!in_map) mapped_ids_.insert(std::upper_bound(mapped_ids_.begin(), mapped_ids_.end(),
                                                       true_id),
                                      true_id);
      break;
    case AssociationOutcome::kDropped:
      ++score_.dropped;
      break;
  }
}

IdAgreement AssociationAgreement(const std::vector<std::pair<int, LandmarkId>>& assigned,
                                 int sightings) {
  std::map<std::pair<int, LandmarkId>, int> shared;
  for (const auto& pair : assigned) {
    if (pair.first >= 0) ++shared[pair];
  }
  std::vector<std::pair<int, std::pair<int, LandmarkId>>> by_count;
  for (const auto& [pair, count] : shared) by_count.push_back({count, pair});
  std::stable_sort(by_count.begin(), by_count.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  IdAgreement out;
  std::set<LandmarkId> theirs_taken;
  int agree = 0;
  for (const auto& [count, pair] : by_count) {
    if (out.pairs.count(pair.first) || theirs_taken.count(pair.second)) continue;
    out.pairs[pair.first] = pair.second;
    theirs_taken.insert(pair.second);
    agree += count;
  }
  out.share = sightings > 0 ? double(agree) / double(sightings) : 1.0;
  return out;
}

}  // namespace slamkit
