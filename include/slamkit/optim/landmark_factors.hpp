#pragma once

#include <Eigen/Core>
#include <ceres/sized_cost_function.h>

#include "slamkit/core/pose2.hpp"

namespace slamkit {

// Factors of a landmark smoother (eval's SmoothLandmarkSlam), whitened by the measurement's
// covariance (r = U e with UᵀU = Σ⁻¹), with analytic Jacobians from Pose2's.

// Odometry as a vector difference: e = (x_i⁻¹ ⊕ x_j) − δ, the heading wrapped. Parameter
// blocks: x_i, x_j (x, y, θ).
class OdometryDeltaFactor final : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  // Throws std::invalid_argument for a covariance that is not positive definite.
  OdometryDeltaFactor(const Pose2& delta, const Eigen::Matrix3d& covariance);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d delta_;
  Eigen::Matrix3d sqrt_information_;
};

// A point landmark seen from a pose, in the pose's frame: e = R(θ)ᵀ (l − t) − z. Parameter
// blocks: the pose (x, y, θ) and the landmark (x, y).
class PosePointFactor final : public ceres::SizedCostFunction<2, 3, 2> {
 public:
  // Throws std::invalid_argument for a covariance that is not positive definite.
  PosePointFactor(const Eigen::Vector2d& z, const Eigen::Matrix2d& covariance);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector2d z_;
  Eigen::Matrix2d sqrt_information_;
};

}  // namespace slamkit
