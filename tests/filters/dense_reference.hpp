#pragma once

#include <Eigen/Dense>
#include <vector>

#include "slamkit/core/angle.hpp"

namespace slamkit::testing {

// The textbook sequential EKF on a dense state (full P, one observation at a time,
// K = P Hᵀ S⁻¹, Joseph form), the reference the block-structured filter must equal.
struct DenseEkf {
  Eigen::VectorXd x;
  Eigen::MatrixXd P;
  std::vector<int> angles;  // state indices wrapped after every update

  void Update(const Eigen::VectorXd& nu, const Eigen::MatrixXd& H, const Eigen::MatrixXd& R) {
    const Eigen::MatrixXd PHt = P * H.transpose();
    const Eigen::MatrixXd S = H * PHt + R;
    const Eigen::MatrixXd K = PHt * S.inverse();
    x += K * nu;
    for (const int i : angles) x[i] = WrapAngle(x[i]);
    // Joseph form (I − KH) P (I − KH)ᵀ + K R Kᵀ multiplied out (P symmetric, HPHᵀ + R = S), so
    // it costs O(n² d), not O(n³): the sanitizer build runs this test code at -O0.
    const Eigen::MatrixXd KPHt_t = K * PHt.transpose();
    P += K * S * K.transpose() - KPHt_t - KPHt_t.transpose();
  }

  // Appends b = g(x, z) with J_b_x (d × n) and J_b_z.
  void Augment(const Eigen::VectorXd& mean, const Eigen::MatrixXd& J_b_x,
               const Eigen::MatrixXd& J_b_z, const Eigen::MatrixXd& R) {
    const int n = static_cast<int>(x.size()), d = static_cast<int>(mean.size());
    Eigen::MatrixXd grown(n + d, n + d);
    grown.topLeftCorner(n, n) = P;
    grown.topRightCorner(n, d) = P * J_b_x.transpose();
    grown.bottomLeftCorner(d, n) = J_b_x * P;
    grown.bottomRightCorner(d, d) = J_b_x * P * J_b_x.transpose() + J_b_z * R * J_b_z.transpose();
    P = grown;
    x.conservativeResize(n + d);
    x.tail(d) = mean;
  }

  // A d_z × n Jacobian that is `J` at columns [offset, offset + J.cols()).
  Eigen::MatrixXd Spread(const Eigen::MatrixXd& J, int offset) const {
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(J.rows(), x.size());
    H.middleCols(offset, J.cols()) = J;
    return H;
  }
};

inline double MaxAbsDiff(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

}  // namespace slamkit::testing
