#include "slamkit/core/gaussian.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace slamkit {

double Gaussian::SquaredMahalanobis(const Eigen::VectorXd& x) const {
  const Eigen::VectorXd d = x - mean;
  return d.dot(covariance.ldlt().solve(d));
}

double SquaredMahalanobis2(const Eigen::Vector2d& nu, const Eigen::Matrix2d& S) {
  return nu.dot(S.inverse() * nu);
}

}  // namespace slamkit
