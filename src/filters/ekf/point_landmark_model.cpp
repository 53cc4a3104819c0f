#include "slamkit/filters/ekf/point_landmark_model.hpp"

namespace slamkit {

BlockPrediction PointLandmarkModel::Predict(const BlockEkf& ekf,
                                            std::span<const int> blocks) const {
  Eigen::Matrix<double, 2, 3> J_z_x;
  Eigen::Matrix2d J_z_l;
  const Eigen::Vector2d l = ekf.Mean(blocks[1]);
  BlockPrediction out;
  out.z = sensor_->Predict(ekf.PoseOf(blocks[0]), l, &J_z_x, &J_z_l);
  out.J_z_blocks.Add(blocks[0], J_z_x);
  out.J_z_blocks.Add(blocks[1], J_z_l);
  return out;
}

BlockVector PointLandmarkModel::Innovation(const BlockVector& z, const BlockVector& z_pred) const {
  return sensor_->Innovation(Eigen::Vector2d(z), Eigen::Vector2d(z_pred));
}

BlockInversion PointLandmarkModel::Invert(const BlockEkf& ekf, std::span<const int> observers,
                                          const BlockVector& z) const {
  Eigen::Matrix<double, 2, 3> J_l_x;
  Eigen::Matrix2d J_l_z;
  BlockInversion out;
  out.mean = sensor_->Invert(ekf.PoseOf(observers[0]), Eigen::Vector2d(z), &J_l_x, &J_l_z);
  out.J_new_blocks.Add(observers[0], J_l_x);
  out.J_new_z = J_l_z;
  return out;
}

bool PointLandmarkModel::Gate(const BlockEkf& ekf, std::span<const int> blocks) const {
  return GateFrom(ekf.PoseOf(blocks[0])).Passes(ekf.Mean(blocks[1]));
}

PointLandmarkModel::ReachGate PointLandmarkModel::GateFrom(const Pose2& observer) const {
  const double reach = sensor_->MaxRange() + margin_m_;
  return {observer.translation(), reach * reach};
}

void PointLandmarkModel::LinearisePosePoint(const Pose2& observer, const Eigen::Vector2d& l,
                                            const Eigen::Vector2d& z,
                                            PosePointObservation& out) const {
  const Eigen::Vector2d z_pred = sensor_->Predict(observer, l, &out.J_pose, &out.J_point);
  out.innovation = sensor_->Innovation(z, z_pred);
}

}  // namespace slamkit
