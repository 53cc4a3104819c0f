#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

namespace slamkit {

// The result of one Kalman correction of a small Gaussian.
template <int kN, int kM>
struct KalmanCorrection {
  Eigen::Matrix<double, kN, 1> mean;
  Eigen::Matrix<double, kN, kN> covariance;
  Eigen::Matrix<double, kM, kM> S;          // innovation covariance H P Hᵀ + R
  Eigen::Matrix<double, kM, 1> innovation;  // as given (already wrapped by the caller's model)
  bool ok = false;  // false when S is not positive definite: mean and covariance unchanged
};

// The EKF correction of a small state (FastSLAM's per-particle landmark EKFs, Montemerlo et al.
// 2002, Eqs. 4-6), with `innovation` = z − h(mean) and `J_z_x` = ∂h/∂x at the mean.
template <int kN, int kM>
KalmanCorrection<kN, kM> KalmanUpdate(const Eigen::Matrix<double, kN, 1>& mean,
                                      const Eigen::Matrix<double, kN, kN>& covariance,
                                      const Eigen::Matrix<double, kM, 1>& innovation,
                                      const Eigen::Matrix<double, kM, kN>& J_z_x,
                                      const Eigen::Matrix<double, kM, kM>& R) {
  // Probabilistic Robotics Table 3.3 with the Joseph form of the covariance, which stays
  // symmetric positive semi-definite under rounding.
  const auto& P = covariance;
  const auto& H = J_z_x;
  KalmanCorrection<kN, kM> out{mean, covariance, H * P * H.transpose() + R, innovation, false};
  const Eigen::LLT<Eigen::Matrix<double, kM, kM>> llt(out.S);
  if (llt.info() != Eigen::Success) return out;
  const Eigen::Matrix<double, kN, kM> K = llt.solve(H * P).transpose();  // P Hᵀ S⁻¹, S symmetric
  const Eigen::Matrix<double, kN, kN> I_KH =
      Eigen::Matrix<double, kN, kN>::Identity(mean.size(), mean.size()) - K * H;
  out.mean = mean + K * innovation;
  out.covariance = I_KH * P * I_KH.transpose() + K * R * K.transpose();
  out.ok = true;
  return out;
}

}  // namespace slamkit
