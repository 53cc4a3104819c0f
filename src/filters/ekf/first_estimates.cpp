#include "slamkit/filters/ekf/first_estimates.hpp"

namespace slamkit {

// Huang, Mourikis, Roumeliotis 2008, Sec. IV: the heading column of Φ_R is
// J·(p̂_{k+1|k} − p̂_{k|k−1}), the prior (not the updated) position at step k.
void FirstEstimatesMotionJacobian(const Pose2& moved, const Pose2& prior, Eigen::Matrix3d* J_x_x) {
  const Eigen::Vector2d dp = moved.translation() - prior.translation();
  (*J_x_x)(0, 2) = -dp.y();
  (*J_x_x)(1, 2) = dp.x();
}

void FirstEstimatesPointModel::Record(int block, const Eigen::Vector2d& l) {
  if (static_cast<int>(first_.size()) <= block) first_.resize(block + 1, Eigen::Vector2d::Zero());
  first_[block] = l;
}

// Huang, Mourikis, Roumeliotis 2008, Sec. IV: H from p̂_{k|k−1} and the landmark's first estimate;
// the innovation z − h(x̂) from the current means.
BlockPrediction FirstEstimatesPointModel::Predict(const BlockEkf& ekf,
                                                  std::span<const int> blocks) const {
  Eigen::Matrix<double, 2, 3> J_z_x;
  Eigen::Matrix2d J_z_l;
  sensor_->Predict(prior_pose_, FirstEstimate(blocks[1]), &J_z_x, &J_z_l);
  BlockPrediction out;
  out.z = sensor_->Predict(ekf.PoseOf(blocks[0]), ekf.Mean(blocks[1]));
  out.J_z_blocks.Add(blocks[0], J_z_x);
  out.J_z_blocks.Add(blocks[1], J_z_l);
  return out;
}

BlockVector FirstEstimatesPointModel::Innovation(const BlockVector& z,
                                                 const BlockVector& z_pred) const {
  return sensor_->Innovation(Eigen::Vector2d(z), Eigen::Vector2d(z_pred));
}

}  // namespace slamkit
