#pragma once

#include "slamkit/models/motion_model.hpp"

namespace slamkit {

struct OdometryParams {
  double sigma_xy_m = 0.04;     // per-step noise of the forward and lateral increments
  double sigma_theta_rad = 1.745e-4;  // per-step heading-increment noise (0.01°)
};

// Odometry increments u = (dx, dy, dθ) measured in the robot frame at the start of the step:
// x' = x ⊕ u. The time step is ignored. When a data set gives each increment's own covariance,
// filters take it in place of Noise() (see EkfSlam::Predict).
class OdometryModel final : public MotionModel {
 public:
  explicit OdometryModel(const OdometryParams& params = {}) : params_(params) {}
  int ControlDim() const override { return 3; }
  Pose2 Move(const Pose2& x, const Control& u, double dt_s, Eigen::Matrix3d* J_out_x = nullptr,
             ControlJacobian* J_out_u = nullptr) const override;
  ControlCovariance Noise(const Control& u, double dt_s) const override;

 private:
  OdometryParams params_;
};

}  // namespace slamkit
