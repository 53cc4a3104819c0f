#include "slamkit/models/unicycle.hpp"

#include <cmath>

namespace slamkit {

Pose2 UnicycleModel::Move(const Pose2& x, const Control& u, double dt_s, Eigen::Matrix3d* J_out_x,
                          ControlJacobian* J_out_u) const {
  const double v = u[0], w = u[1];
  const double a = x.theta() + 0.5 * w * dt_s;  // midpoint heading
  const double c = std::cos(a), s = std::sin(a);
  const double d = v * dt_s;
  if (J_out_x) *J_out_x << 1, 0, -d * s, 0, 1, d * c, 0, 0, 1;
  if (J_out_u) {
    J_out_u->resize(3, 2);
    *J_out_u << dt_s * c, -0.5 * d * dt_s * s, dt_s * s, 0.5 * d * dt_s * c, 0, dt_s;
  }
  return {x.x() + d * c, x.y() + d * s, x.theta() + w * dt_s};
}

ControlCovariance UnicycleModel::Noise(const Control& /*u*/, double /*dt_s*/) const {
  ControlCovariance q = ControlCovariance::Zero(2, 2);
  q(0, 0) = params_.sigma_v_mps * params_.sigma_v_mps;
  q(1, 1) = params_.sigma_omega_radps * params_.sigma_omega_radps;
  return q;
}

}  // namespace slamkit
