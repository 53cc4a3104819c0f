#pragma once

#include <Eigen/Core>

namespace slamkit {

// A multivariate normal N(mean, covariance).
struct Gaussian {
  Eigen::VectorXd mean;
  Eigen::MatrixXd covariance;

  // Squared Mahalanobis distance of `x` from the mean.
  double SquaredMahalanobis(const Eigen::VectorXd& x) const;
};

// Squared Mahalanobis distance ν^T S^-1 ν for a 2-vector innovation (the EKF's hot path).
double SquaredMahalanobis2(const Eigen::Vector2d& nu, const Eigen::Matrix2d& S);

}  // namespace slamkit
