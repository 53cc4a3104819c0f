#include "slamkit/optim/pose_graph_factors.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

using RowMajor33 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// S with dR(θ)/dθ = S R(θ).
const Eigen::Matrix2d& Skew() {
  static const Eigen::Matrix2d S = (Eigen::Matrix2d() << 0.0, -1.0, 1.0, 0.0).finished();
  return S;
}

}  // namespace

Eigen::Matrix3d SqrtInformation(const Eigen::Matrix3d& information) {
  const Eigen::LLT<Eigen::Matrix3d> llt(information);
  if (!information.allFinite() || !information.isApprox(information.transpose()) ||
      llt.info() != Eigen::Success) {
    throw std::invalid_argument("pose graph: an information matrix is not positive definite");
  }
  return llt.matrixU();
}

SeSyncWeights SeSyncWeightsOf(const PoseGraphEdge& edge) {
  const Eigen::Matrix2d translation_information = edge.information.topLeftCorner<2, 2>();
  return {edge.information(2, 2), 2.0 / translation_information.inverse().trace()};
}

RelativePoseChi2Factor::RelativePoseChi2Factor(const PoseGraphEdge& edge)
    : t_ij_(edge.measurement.translation()),
      theta_ij_(edge.measurement.theta()),
      R_ij_transpose_(Eigen::Rotation2Dd(edge.measurement.theta()).toRotationMatrix().transpose()),
      sqrt_information_(SqrtInformation(edge.information)) {}

bool RelativePoseChi2Factor::Evaluate(double const* const* parameters, double* residuals,
                                      double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> xi(parameters[0]), xj(parameters[1]);
  const Eigen::Matrix2d Ri_t = Eigen::Rotation2Dd(xi.z()).toRotationMatrix().transpose();
  const Eigen::Vector2d d = xj.head<2>() - xi.head<2>();
  Eigen::Vector3d e;
  e.head<2>() = R_ij_transpose_ * (Ri_t * d - t_ij_);
  e.z() = WrapAngle(xj.z() - xi.z() - theta_ij_);
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = sqrt_information_ * e;
  if (jacobians == nullptr) return true;
  const Eigen::Matrix2d A = R_ij_transpose_ * Ri_t;
  if (jacobians[0] != nullptr) {
    RowMajor33 J = RowMajor33::Zero();
    J.topLeftCorner<2, 2>() = -A;
    J.block<2, 1>(0, 2) = -A * Skew() * d;
    J(2, 2) = -1.0;
    Eigen::Map<RowMajor33> J_r_xi(jacobians[0]);
    J_r_xi = sqrt_information_ * J;
  }
  if (jacobians[1] != nullptr) {
    RowMajor33 J = RowMajor33::Zero();
    J.topLeftCorner<2, 2>() = A;
    J(2, 2) = 1.0;
    Eigen::Map<RowMajor33> J_r_xj(jacobians[1]);
    J_r_xj = sqrt_information_ * J;
  }
  return true;
}

RelativePoseSeSyncFactor::RelativePoseSeSyncFactor(const PoseGraphEdge& edge)
    : t_ij_(edge.measurement.translation()), theta_ij_(edge.measurement.theta()) {
  const SeSyncWeights w = SeSyncWeightsOf(edge);
  if (!(w.kappa > 0.0 && w.tau > 0.0 && std::isfinite(w.kappa) && std::isfinite(w.tau))) {
    throw std::invalid_argument("pose graph: SE-Sync weights need positive definite information");
  }
  sqrt_tau_ = std::sqrt(w.tau);
  sqrt_8kappa_ = std::sqrt(8.0 * w.kappa);
}

bool RelativePoseSeSyncFactor::Evaluate(double const* const* parameters, double* residuals,
                                        double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> xi(parameters[0]), xj(parameters[1]);
  const Eigen::Matrix2d Ri = Eigen::Rotation2Dd(xi.z()).toRotationMatrix();
  const double half = 0.5 * (xj.z() - xi.z() - theta_ij_);  // sin² is 2π-periodic: no wrap
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r.head<2>() = sqrt_tau_ * (xj.head<2>() - xi.head<2>() - Ri * t_ij_);
  r.z() = sqrt_8kappa_ * std::sin(half);
  if (jacobians == nullptr) return true;
  const double dr_dtheta_j = 0.5 * sqrt_8kappa_ * std::cos(half);
  if (jacobians[0] != nullptr) {
    Eigen::Map<RowMajor33> J(jacobians[0]);
    J.setZero();
    J.topLeftCorner<2, 2>() = -sqrt_tau_ * Eigen::Matrix2d::Identity();
    J.block<2, 1>(0, 2) = -sqrt_tau_ * Skew() * Ri * t_ij_;
    J(2, 2) = -dr_dtheta_j;
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<RowMajor33> J(jacobians[1]);
    J.setZero();
    J.topLeftCorner<2, 2>() = sqrt_tau_ * Eigen::Matrix2d::Identity();
    J(2, 2) = dr_dtheta_j;
  }
  return true;
}

PosePriorFactor::PosePriorFactor(const Pose2& prior, const Eigen::Matrix3d& information)
    : prior_(prior.vector()), sqrt_information_(SqrtInformation(information)) {}

bool PosePriorFactor::Evaluate(double const* const* parameters, double* residuals,
                               double** jacobians) const {
  const Eigen::Map<const Eigen::Vector3d> x(parameters[0]);
  Eigen::Vector3d e = x - prior_;
  e.z() = WrapAngle(e.z());
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = sqrt_information_ * e;
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    Eigen::Map<RowMajor33> J_r_x(jacobians[0]);
    J_r_x = sqrt_information_;
  }
  return true;
}

}  // namespace slamkit
