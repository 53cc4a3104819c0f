#pragma once

#include "slamkit/models/motion_model.hpp"

namespace slamkit {

struct UnicycleParams {
  double sigma_v_mps = 0.1;        // standard deviation of the speed noise
  double sigma_omega_radps = 0.02; // standard deviation of the turn-rate noise
};

// Differential-drive robot with control u = (v [m/s], ω [rad/s]), integrated at the midpoint
// heading: x' = x + vΔt cos(θ + ωΔt/2), y' = y + vΔt sin(θ + ωΔt/2), θ' = θ + ωΔt.
class UnicycleModel final : public MotionModel {
 public:
  explicit UnicycleModel(const UnicycleParams& params = {}) : params_(params) {}
  int ControlDim() const override { return 2; }
  Pose2 Move(const Pose2& x, const Control& u, double dt_s, Eigen::Matrix3d* J_out_x = nullptr,
             ControlJacobian* J_out_u = nullptr) const override;
  ControlCovariance Noise(const Control& u, double dt_s) const override;

 private:
  UnicycleParams params_;
};

}  // namespace slamkit
