#include "slamkit/filters/ekf_slam/active_area.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace slamkit {

void ActiveArea::Synchronise(BlockEkf& ekf) {
  if (!ekf.IsCompressed()) return;
  const auto start = std::chrono::steady_clock::now();
  ekf.Synchronise();
  stats_.global_update_s +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++stats_.global_updates;
}

void ActiveArea::Maintain(BlockEkf& ekf, int pose_block, std::span<const int> points,
                          double reach_m) {
  Maintain(ekf, pose_block, points, reach_m, [&ekf](int b, const Eigen::Vector2d& p) {
    return (ekf.Mean(b) - p).squaredNorm();
  });
}

// Guivant & Nebot 2001, Sec. IV: the area is left when the vehicle can reach beyond it.
void ActiveArea::Maintain(BlockEkf& ekf, int pose_block, std::span<const int> landmarks,
                          double reach_m, const LandmarkDistanceSq& distance_sq) {
  const Eigen::Vector2d position = ekf.PoseOf(pose_block).translation();
  const double hysteresis_m = params_.hysteresis_fraction * reach_m;
  if (ekf.IsCompressed() && (position - centre_).norm() <= hysteresis_m) {
    stats_.max_active_size = std::max(stats_.max_active_size, ekf.ActiveSize());
    return;
  }
  Synchronise(ekf);
  const Eigen::Matrix2d P_xy = ekf.PoseCovarianceOf(pose_block).topLeftCorner<2, 2>();
  const double sigma_m =
      std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(P_xy).eigenvalues()[1]));
  const double radius_m = hysteresis_m + reach_m + params_.sigma_factor * sigma_m;
  centre_ = position;
  std::vector<int> active = {pose_block};
  for (const int b : landmarks) {
    if (distance_sq(b, centre_) <= radius_m * radius_m) active.push_back(b);
  }
  ekf.Compress(active);
  stats_.max_active_size = std::max(stats_.max_active_size, ekf.ActiveSize());
}

}  // namespace slamkit
