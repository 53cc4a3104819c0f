#include "slamkit/optim/landmark_factors.hpp"

#include <stdexcept>

#include <Eigen/Cholesky>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

// U with UᵀU = Σ⁻¹.
template <int N>
Eigen::Matrix<double, N, N> SqrtInverse(const Eigen::Matrix<double, N, N>& covariance) {
  const Eigen::LLT<Eigen::Matrix<double, N, N>> llt(covariance);
  if (!covariance.allFinite() || llt.info() != Eigen::Success) {
    throw std::invalid_argument("a measurement covariance is not positive definite");
  }
  const Eigen::Matrix<double, N, N> information =
      llt.solve(Eigen::Matrix<double, N, N>::Identity());
  return Eigen::LLT<Eigen::Matrix<double, N, N>>(0.5 * (information + information.transpose()))
      .matrixU();
}

}  // namespace

OdometryDeltaFactor::OdometryDeltaFactor(const Pose2& delta, const Eigen::Matrix3d& covariance)
    : delta_(delta.vector()), sqrt_information_(SqrtInverse<3>(covariance)) {}

bool OdometryDeltaFactor::Evaluate(double const* const* parameters, double* residuals,
                                   double** jacobians) const {
  const Pose2 xi(parameters[0][0], parameters[0][1], parameters[0][2]);
  const Pose2 xj(parameters[1][0], parameters[1][1], parameters[1][2]);
  Eigen::Matrix3d J_d_i, J_d_j;
  Eigen::Vector3d e = xi.Between(xj, &J_d_i, &J_d_j).vector() - delta_;
  e.z() = WrapAngle(e.z());
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = sqrt_information_ * e;
  if (jacobians == nullptr) return true;
  using RowMajor33 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  if (jacobians[0] != nullptr) {
    Eigen::Map<RowMajor33> J_r_xi(jacobians[0]);
    J_r_xi = sqrt_information_ * J_d_i;
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<RowMajor33> J_r_xj(jacobians[1]);
    J_r_xj = sqrt_information_ * J_d_j;
  }
  return true;
}

PosePointFactor::PosePointFactor(const Eigen::Vector2d& z, const Eigen::Matrix2d& covariance)
    : z_(z), sqrt_information_(SqrtInverse<2>(covariance)) {}

bool PosePointFactor::Evaluate(double const* const* parameters, double* residuals,
                               double** jacobians) const {
  const Pose2 x(parameters[0][0], parameters[0][1], parameters[0][2]);
  const Eigen::Map<const Eigen::Vector2d> l(parameters[1]);
  Eigen::Matrix<double, 2, 3> J_z_x;
  Eigen::Matrix2d J_z_l;
  Eigen::Map<Eigen::Vector2d> r(residuals);
  r = sqrt_information_ * (x.TransformTo(l, &J_z_x, &J_z_l) - z_);
  if (jacobians == nullptr) return true;
  if (jacobians[0] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> J_r_x(jacobians[0]);
    J_r_x = sqrt_information_ * J_z_x;
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 2, 2, Eigen::RowMajor>> J_r_l(jacobians[1]);
    J_r_l = sqrt_information_ * J_z_l;
  }
  return true;
}

}  // namespace slamkit
