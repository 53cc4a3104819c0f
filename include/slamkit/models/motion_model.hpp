#pragma once

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"

namespace slamkit {

// A control vector of at most 3 components, kept on the stack.
using Control = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 3, 1>;
using ControlJacobian = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3>;
using ControlCovariance = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 3, 3>;

// A vehicle motion model x' = f(x, u, dt) with its noise in control space. Filters linearise it
// through the two Jacobians and map the control covariance into state space as J_x_u Q J_x_uᵀ.
class MotionModel {
 public:
  virtual ~MotionModel() = default;

  virtual int ControlDim() const = 0;
  // The mean motion. J_out_x is 3×3, J_out_u is 3×ControlDim().
  virtual Pose2 Move(const Pose2& x, const Control& u, double dt_s,
                     Eigen::Matrix3d* J_out_x = nullptr,
                     ControlJacobian* J_out_u = nullptr) const = 0;
  // Covariance of the control noise for a step with control `u` (ControlDim() square).
  virtual ControlCovariance Noise(const Control& u, double dt_s) const = 0;
};

}  // namespace slamkit
