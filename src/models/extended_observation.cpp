#include "slamkit/models/extended_observation.hpp"

#include <cmath>

#include "slamkit/core/angle.hpp"

namespace slamkit {

RangeBearing PredictVehicleSighting(const Pose2& a, const Pose2& b,
                                    Eigen::Matrix<double, 2, 3>* J_out_a,
                                    Eigen::Matrix<double, 2, 3>* J_out_b) {
  Eigen::Matrix2d J_z_position;
  const RangeBearing z = PredictRangeBearing(a, b.translation(), J_out_a,
                                             J_out_b ? &J_z_position : nullptr);
  if (J_out_b) *J_out_b << J_z_position, Eigen::Vector2d::Zero();
  return z;
}

// SPEC S3, seed 002 Eqs. 8-14 (z_ab = z_a + z_b of its Fig. 1, as points in a's frame).
RangeBearing ComposeExtendedObservation(const RangeBearing& z_ab, const RangeBearing& z_bf,
                                        double relative_heading_rad,
                                        ExtendedObservationJacobian* J_out_in) {
  const double c_ab = std::cos(z_ab.bearing_rad), s_ab = std::sin(z_ab.bearing_rad);
  const double a_bf = relative_heading_rad + z_bf.bearing_rad;
  const double c_bf = std::cos(a_bf), s_bf = std::sin(a_bf);
  const Eigen::Vector2d t(z_ab.range_m * c_ab + z_bf.range_m * c_bf,
                          z_ab.range_m * s_ab + z_bf.range_m * s_bf);
  const double q = t.squaredNorm();
  const double r = std::sqrt(q);
  if (J_out_in) {
    // ∂t/∂inputs, then ∂(r, β)/∂t = [tᵀ/r; (−t_y, t_x)/q].
    Eigen::Matrix<double, 2, 5> J_t;
    J_t << c_ab, -z_ab.range_m * s_ab, c_bf, -z_bf.range_m * s_bf, -z_bf.range_m * s_bf,
        s_ab, z_ab.range_m * c_ab, s_bf, z_bf.range_m * c_bf, z_bf.range_m * c_bf;
    Eigen::Matrix2d J_polar;
    J_polar << t.x() / r, t.y() / r, -t.y() / q, t.x() / q;
    *J_out_in = J_polar * J_t;
  }
  return {r, WrapAngle(std::atan2(t.y(), t.x()))};
}

Eigen::Matrix2d ExtendedObservationCovariance(const ExtendedObservationJacobian& J,
                                              const Eigen::Matrix2d& R_ab,
                                              const Eigen::Matrix2d& R_bf,
                                              double relative_heading_variance_rad2) {
  Eigen::Matrix<double, 5, 5> inputs = Eigen::Matrix<double, 5, 5>::Zero();
  inputs.topLeftCorner<2, 2>() = R_ab;
  inputs.block<2, 2>(2, 2) = R_bf;
  inputs(4, 4) = relative_heading_variance_rad2;
  return J * inputs * J.transpose();
}

}  // namespace slamkit
