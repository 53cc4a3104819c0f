#include "slamkit/models/car_like.hpp"

#include <cmath>

namespace slamkit {

// SPEC S2, Eq. 2.
Pose2 CarLikeModel::Move(const Pose2& x, const Control& u, double dt_s, Eigen::Matrix3d* J_out_x,
                         ControlJacobian* J_out_u) const {
  const double v = u[0], g = u[1];
  const double b = params_.wheelbase_m;
  const double a = x.theta() + g;
  const double c = std::cos(a), s = std::sin(a);
  const double d = v * dt_s;
  if (J_out_x) *J_out_x << 1, 0, -d * s, 0, 1, d * c, 0, 0, 1;
  if (J_out_u) {
    J_out_u->resize(3, 2);
    *J_out_u << dt_s * c, -d * s, dt_s * s, d * c, dt_s * std::sin(g) / b, d * std::cos(g) / b;
  }
  return {x.x() + d * c, x.y() + d * s, x.theta() + d * std::sin(g) / b};
}

ControlCovariance CarLikeModel::Noise(const Control& /*u*/, double /*dt_s*/) const {
  ControlCovariance q = ControlCovariance::Zero(2, 2);
  q(0, 0) = params_.sigma_v_mps * params_.sigma_v_mps;
  q(1, 1) = params_.sigma_steer_rad * params_.sigma_steer_rad;
  return q;
}

}  // namespace slamkit
