#pragma once

#include "slamkit/models/motion_model.hpp"

namespace slamkit {

struct CarLikeParams {
  double wheelbase_m = 4.0;        // B in SPEC S2, Eq. 2
  double sigma_v_mps = 0.3;        // standard deviation of the speed noise
  double sigma_steer_rad = 0.0524; // standard deviation of the steering-angle noise (3°)
};

// SPEC S2, Eq. 2: car-like vehicle with control u = (v [m/s], G [rad] steering angle):
// x' = x + vΔT cos(θ + G), y' = y + vΔT sin(θ + G), θ' = θ + vΔT sin(G) / B.
class CarLikeModel final : public MotionModel {
 public:
  explicit CarLikeModel(const CarLikeParams& params = {}) : params_(params) {}
  int ControlDim() const override { return 2; }
  Pose2 Move(const Pose2& x, const Control& u, double dt_s, Eigen::Matrix3d* J_out_x = nullptr,
             ControlJacobian* J_out_u = nullptr) const override;
  ControlCovariance Noise(const Control& u, double dt_s) const override;
  const CarLikeParams& params() const { return params_; }

 private:
  CarLikeParams params_;
};

}  // namespace slamkit
