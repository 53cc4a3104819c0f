#include "slamkit/filters/grid/match_constraints.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "slamkit/core/angle.hpp"

namespace slamkit {

std::vector<Eigen::Vector2d> EstimateNormals(const std::vector<Eigen::Vector2d>& ends,
                                             const MatchConstraintParams& params) {
  const int n = static_cast<int>(ends.size());
  std::vector<Eigen::Vector2d> normals(n, Eigen::Vector2d::Zero());
  const double radius_sq = params.normal_radius_m * params.normal_radius_m;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    Eigen::Matrix2d outer = Eigen::Matrix2d::Zero();
    int count = 0;
    for (int j = std::max(0, i - params.normal_neighbours);
         j <= std::min(n - 1, i + params.normal_neighbours); ++j) {
      if ((ends[j] - ends[i]).squaredNorm() > radius_sq) continue;
      sum += ends[j];
      outer += ends[j] * ends[j].transpose();
      ++count;
    }
    if (count < 3) continue;
    const Eigen::Vector2d mean = sum / count;
    const Eigen::Matrix2d scatter = outer / count - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(scatter);
    const Eigen::Vector2d spread = eigen.eigenvalues();  // ascending
    if (spread(1) <= 0.0 || spread(0) > params.max_normal_spread * spread(1)) continue;
    normals[i] = eigen.eigenvectors().col(0);
  }
  return normals;
}

MatchInformation ComputeMatchInformation(const std::vector<Eigen::Vector2d>& ends,
                                         const std::vector<Eigen::Vector2d>& normals,
                                         const std::vector<std::uint8_t>& hit) {
  MatchInformation out;
  double range_sq = 0.0;
  int used = 0;
  for (std::size_t i = 0; i < ends.size(); ++i) {
    if (!hit[i] || normals[i].isZero()) continue;
    range_sq += ends[i].squaredNorm();
    ++used;
  }
  if (used == 0) return out;
  out.length_m = std::max(std::sqrt(range_sq / used), 1e-3);
  for (std::size_t i = 0; i < ends.size(); ++i) {
    if (!hit[i] || normals[i].isZero()) continue;
    const Eigen::Vector2d& n = normals[i];
    const Eigen::Vector2d& p = ends[i];
    // d/dθ of n·(R p) at R = I is n·(−p.y, p.x).
    const Eigen::Vector3d J(n.x(), n.y(), (n.y() * p.x() - n.x() * p.y()) / out.length_m);
    out.information += J * J.transpose();
  }
  return out;
}

MatchConstraints FindConstraints(const MatchInformation& info,
                                 const MatchConstraintParams& params) {
  MatchConstraints out;
  if (params.min_information_ratio <= 0.0) return out;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(info.information);
  const Eigen::Vector3d values = eigen.eigenvalues();  // ascending
  if (values(2) <= 0.0) return out;  // no information at all: nothing to say which way
  // The projection is taken in (x, y, ℓθ), where the eigenvectors are, and brought back.
  Eigen::Matrix3d keep_scaled = Eigen::Matrix3d::Identity();
  for (int k = 0; k < 2; ++k) {
    if (values(k) >= params.min_information_ratio * values(2)) continue;
    const Eigen::Vector3d u = eigen.eigenvectors().col(k);
    keep_scaled -= u * u.transpose();
    ++out.unconstrained;
  }
  const Eigen::Vector3d scale(1.0, 1.0, info.length_m);
  out.keep = scale.cwiseInverse().asDiagonal() * keep_scaled * scale.asDiagonal();
  return out;
}

Eigen::Matrix3d MatchConstraints::KeepInWorld(double theta_rad) const {
  if (unconstrained == 0) return keep;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  rotation.topLeftCorner<2, 2>() = Pose2(0.0, 0.0, theta_rad).rotation();
  return rotation * keep * rotation.transpose();
}

Pose2 KeepGuessAlong(const Pose2& initial, const Pose2& match,
                     const MatchConstraints& constraints) {
  if (constraints.unconstrained == 0) return match;
  const Eigen::Vector3d move(match.x() - initial.x(), match.y() - initial.y(),
                             WrapAngle(match.theta() - initial.theta()));
  const Eigen::Vector3d kept = constraints.KeepInWorld(initial.theta()) * move;
  return Pose2(initial.x() + kept.x(), initial.y() + kept.y(),
               WrapAngle(initial.theta() + kept.z()));
}

}  // namespace slamkit
