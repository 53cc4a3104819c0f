#pragma once

#include <Eigen/Core>
#include <vector>

#include "slamkit/core/pose2.hpp"
#include "slamkit/filters/ekf/observation_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// Where an EKF evaluates its Jacobians (the innovation z − h(x̂) always uses the current means).
enum class JacobianEstimates {
  // At the latest estimates: the textbook EKF (Probabilistic Robotics Tables 10.1-10.2).
  kCurrent,
  // First-estimates Jacobians (FEJ-EKF; Huang, Mourikis, Roumeliotis 2008, Sec. IV): the motion
  // Jacobian from the predicted poses, the measurement Jacobian from the scan's predicted pose
  // and each landmark's first estimate, so that the linearised system keeps the three
  // unobservable directions (global translation and rotation) of the true one.
  kFirstEstimates,
};

// The FEJ motion Jacobian, for a motion of the form p' = p + R(θ)·δ(u), θ' = θ + Δθ(u) (the
// car-like, unicycle and odometry models): Φ = [[I₂, J·(p̂_{k+1|k} − p̂_{k|k−1})], [0, 1]] with
// J = [[0, −1], [1, 0]], `moved` the new predicted pose and `prior` the previous predicted one
// (Huang, Mourikis, Roumeliotis 2008, Sec. IV). Overwrites J_x_x's heading column.
void FirstEstimatesMotionJacobian(const Pose2& moved, const Pose2& prior, Eigen::Matrix3d* J_x_x);

// A point-landmark sensor as the observation model of FEJ updates: blocks are {pose, landmark},
// the predicted measurement is h at the current means, its Jacobians are the sensor's at the
// recorded prior pose and the landmark's recorded first estimate (Huang, Mourikis, Roumeliotis
// 2008, Sec. IV). Only the update's model: association and augmentation use the
// current estimates.
class FirstEstimatesPointModel final : public ObservationModel {
 public:
  // `sensor` must outlive the model.
  explicit FirstEstimatesPointModel(const PointSensorModel& sensor) : sensor_(&sensor) {}

  // Forgets all first estimates (a filter's Reset()).
  void Clear() { first_.clear(); }
  // The pose x̂_{k|k−1} after the latest prediction: every update until the next one is
  // linearised there, whatever the sequential updates of the scan did to the pose.
  void SetPriorPose(const Pose2& x) { prior_pose_ = x; }
  const Pose2& prior_pose() const { return prior_pose_; }
  // The first estimate of the landmark in BlockEkf block `block` (its initialised mean).
  void Record(int block, const Eigen::Vector2d& l);
  const Eigen::Vector2d& FirstEstimate(int block) const { return first_[block]; }

  int MeasurementDim() const override { return 2; }
  BlockPrediction Predict(const BlockEkf& ekf, std::span<const int> blocks) const override;
  BlockVector Innovation(const BlockVector& z, const BlockVector& z_pred) const override;

 private:
  const PointSensorModel* sensor_;
  Pose2 prior_pose_;
  std::vector<Eigen::Vector2d> first_;  // by block index
};

}  // namespace slamkit
