#include "slamkit/eval/errors.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace slamkit {

double Nees(const Eigen::Vector3d& error, const Eigen::Matrix3d& covariance) {
  return error.dot(covariance.ldlt().solve(error));
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

}  // namespace slamkit
