#pragma once

#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "slamkit/filters/ekf_slam.hpp"
#include "slamkit/filters/landmark_slam.hpp"

namespace slamkit {

// EkfSlam seen through LandmarkSlamFilter, so that the evaluation harness uses the interface only.
// Temporary: this adapter goes once EkfSlam (being redesigned) implements LandmarkSlamFilter
// itself; then EkfSlamFactory builds EkfSlam directly.
class EkfSlamAdapter final : public LandmarkSlamFilter {
 public:
  EkfSlamAdapter(const EkfSlamParams& params, std::unique_ptr<MotionModel> motion,
                 std::unique_ptr<PointSensorModel> sensor)
      : slam_(params, std::move(motion), std::move(sensor)) {}

  void Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov) override {
    slam_.Reset(pose, pose_cov);
  }
  void Predict(const Control& u, double dt_s,
               const ControlCovariance* control_noise = nullptr) override {
    slam_.Predict(u, dt_s, control_noise);
  }
  std::vector<AssociationDecision> Update(
      std::span<const PointObservation> observations) override {
    return slam_.Update(observations);
  }
  Pose2 PoseEstimate() const override { return slam_.pose(); }
  Eigen::Matrix3d PoseCovariance() const override { return slam_.PoseCovariance(); }
  int NumLandmarks() const override { return slam_.NumLandmarks(); }
  LandmarkMap Map() const override { return slam_.Map(); }

 private:
  EkfSlam slam_;
};

}  // namespace slamkit
