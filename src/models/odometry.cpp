#include "slamkit/models/odometry.hpp"

namespace slamkit {

Pose2 OdometryModel::Move(const Pose2& x, const Control& u, double /*dt_s*/,
                          Eigen::Matrix3d* J_out_x, ControlJacobian* J_out_u) const {
  Eigen::Matrix3d J_u;
  const Pose2 out = x.Compose(Pose2(u[0], u[1], u[2]), J_out_x, J_out_u ? &J_u : nullptr);
  if (J_out_u) *J_out_u = J_u;
  return out;
}

ControlCovariance OdometryModel::Noise(const Control& /*u*/, double /*dt_s*/) const {
  ControlCovariance q = ControlCovariance::Zero(3, 3);
  q(0, 0) = q(1, 1) = params_.sigma_xy_m * params_.sigma_xy_m;
  q(2, 2) = params_.sigma_theta_rad * params_.sigma_theta_rad;
  return q;
}

}  // namespace slamkit
