#include "slamkit/core/pose2.hpp"

#include <cmath>

namespace slamkit {

Eigen::Matrix2d Pose2::rotation() const {
  const double c = std::cos(theta_), s = std::sin(theta_);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

Pose2 Pose2::Compose(const Pose2& other, Eigen::Matrix3d* J_out_this,
                     Eigen::Matrix3d* J_out_other) const {
  const double c = std::cos(theta_), s = std::sin(theta_);
  const double dx = c * other.x_ - s * other.y_;
  const double dy = s * other.x_ + c * other.y_;
  if (J_out_this) {
    *J_out_this << 1, 0, -dy, 0, 1, dx, 0, 0, 1;
  }
  if (J_out_other) {
    *J_out_other << c, -s, 0, s, c, 0, 0, 0, 1;
  }
  return {x_ + dx, y_ + dy, theta_ + other.theta_};
}

Pose2 Pose2::Inverse(Eigen::Matrix3d* J_out_this) const {
  const double c = std::cos(theta_), s = std::sin(theta_);
  const double ix = -c * x_ - s * y_;
  const double iy = s * x_ - c * y_;
  if (J_out_this) {
    // d(ix)/dtheta = s x - c y = iy; d(iy)/dtheta = c x + s y = -ix.
    *J_out_this << -c, -s, iy, s, -c, -ix, 0, 0, -1;
  }
  return {ix, iy, -theta_};
}

Pose2 Pose2::Between(const Pose2& other, Eigen::Matrix3d* J_out_this,
                     Eigen::Matrix3d* J_out_other) const {
  Eigen::Matrix3d J_inv_this, J_out_inv;
  const Pose2 inv = Inverse(J_out_this ? &J_inv_this : nullptr);
  const Pose2 out = inv.Compose(other, J_out_this ? &J_out_inv : nullptr, J_out_other);
  if (J_out_this) *J_out_this = J_out_inv * J_inv_this;
  return out;
}

Eigen::Vector2d Pose2::TransformFrom(const Eigen::Vector2d& p,
                                     Eigen::Matrix<double, 2, 3>* J_out_this,
                                     Eigen::Matrix2d* J_out_p) const {
  const double c = std::cos(theta_), s = std::sin(theta_);
  const double rx = c * p.x() - s * p.y();
  const double ry = s * p.x() + c * p.y();
  if (J_out_this) *J_out_this << 1, 0, -ry, 0, 1, rx;
  if (J_out_p) *J_out_p << c, -s, s, c;
  return {x_ + rx, y_ + ry};
}

Eigen::Vector2d Pose2::TransformTo(const Eigen::Vector2d& p,
                                   Eigen::Matrix<double, 2, 3>* J_out_this,
                                   Eigen::Matrix2d* J_out_p) const {
  const double c = std::cos(theta_), s = std::sin(theta_);
  const double dx = p.x() - x_, dy = p.y() - y_;
  const double bx = c * dx + s * dy;
  const double by = -s * dx + c * dy;
  if (J_out_this) *J_out_this << -c, -s, by, s, -c, -bx;
  if (J_out_p) *J_out_p << c, s, -s, c;
  return {bx, by};
}

Eigen::Vector3d PoseError(const Pose2& estimate, const Pose2& truth) {
  return {estimate.x() - truth.x(), estimate.y() - truth.y(),
          WrapAngle(estimate.theta() - truth.theta())};
}

}  // namespace slamkit
