#include "slamkit/models/range_bearing.hpp"

#include <cmath>

namespace slamkit {

// SPEC S2, Eq. 3.
RangeBearing PredictRangeBearing(const Pose2& x, const Eigen::Vector2d& l,
                                 Eigen::Matrix<double, 2, 3>* J_out_x, Eigen::Matrix2d* J_out_l) {
  const double dx = l.x() - x.x(), dy = l.y() - x.y();
  const double q = dx * dx + dy * dy;
  const double r = std::sqrt(q);
  if (J_out_x) *J_out_x << -dx / r, -dy / r, 0, dy / q, -dx / q, -1;
  if (J_out_l) *J_out_l << dx / r, dy / r, -dy / q, dx / q;
  return {r, WrapAngle(std::atan2(dy, dx) - x.theta())};
}

// SPEC S2, Eq. 8.
Eigen::Vector2d InvertRangeBearing(const Pose2& x, const RangeBearing& z,
                                   Eigen::Matrix<double, 2, 3>* J_out_x, Eigen::Matrix2d* J_out_z) {
  const double a = x.theta() + z.bearing_rad;
  const double c = std::cos(a), s = std::sin(a);
  const double r = z.range_m;
  if (J_out_x) *J_out_x << 1, 0, -r * s, 0, 1, r * c;
  if (J_out_z) *J_out_z << c, -r * s, s, r * c;
  return {x.x() + r * c, x.y() + r * s};
}

Eigen::Vector2d RangeBearingModel::Predict(const Pose2& x, const Eigen::Vector2d& l,
                                           Eigen::Matrix<double, 2, 3>* J_out_x,
                                           Eigen::Matrix2d* J_out_l) const {
  const RangeBearing z = PredictRangeBearing(x, l, J_out_x, J_out_l);
  return {z.range_m, z.bearing_rad};
}

Eigen::Vector2d RangeBearingModel::Invert(const Pose2& x, const Eigen::Vector2d& z,
                                          Eigen::Matrix<double, 2, 3>* J_out_x,
                                          Eigen::Matrix2d* J_out_z) const {
  return InvertRangeBearing(x, {z[0], z[1]}, J_out_x, J_out_z);
}

Eigen::Vector2d RangeBearingModel::Innovation(const Eigen::Vector2d& z,
                                              const Eigen::Vector2d& z_pred) const {
  return {z[0] - z_pred[0], WrapAngle(z[1] - z_pred[1])};
}

bool RangeBearingModel::IsVisible(const Pose2& x, const Eigen::Vector2d& l) const {
  const RangeBearing z = PredictRangeBearing(x, l);
  return z.range_m <= params_.max_range_m && z.range_m >= params_.min_range_m &&
         std::abs(z.bearing_rad) <= 0.5 * params_.fov_rad;
}

Eigen::Matrix2d RangeBearingModel::NoiseCovariance() const {
  return Eigen::Vector2d(params_.sigma_range_m * params_.sigma_range_m,
                         params_.sigma_bearing_rad * params_.sigma_bearing_rad)
      .asDiagonal();
}

Eigen::Matrix2d RangeBearingCovariance(const Eigen::Vector2d& z, double sigma_range_m,
                                       double sigma_bearing_rad) {
  Eigen::Matrix2d J_xy_rb;
  InvertRangeBearing(Pose2(), {z.norm(), std::atan2(z.y(), z.x())}, nullptr, &J_xy_rb);
  const Eigen::Vector2d variances(sigma_range_m * sigma_range_m,
                                  sigma_bearing_rad * sigma_bearing_rad);
  return J_xy_rb * variances.asDiagonal() * J_xy_rb.transpose();
}

}  // namespace slamkit
