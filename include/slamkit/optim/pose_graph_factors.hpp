#pragma once

#include <Eigen/Core>
#include <ceres/sized_cost_function.h>

#include "slamkit/core/pose_graph.hpp"

namespace slamkit {

// Residuals of one relative-pose measurement Z_ij between poses x_i = (t_i, θ_i) and
// x_j = (t_j, θ_j), each a parameter block of 3 doubles (x, y, θ; θ unbounded, the residual wraps
// it). Both are ceres::SizedCostFunction with analytic Jacobians (tested against numeric ones).

// g2o's error, whitened: r = U e with UᵀU = Ω (the edge's information), so |r|² = eᵀ Ω e, where
// e = (R_ijᵀ (R_iᵀ (t_j − t_i) − t_ij), wrap(θ_j − θ_i − θ_ij)).
// Σ |r|² over the edges is the graph's χ².
class RelativePoseChi2Factor final : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  explicit RelativePoseChi2Factor(const PoseGraphEdge& edge);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector2d t_ij_;
  double theta_ij_;
  Eigen::Matrix2d R_ij_transpose_;
  Eigen::Matrix3d sqrt_information_;  // upper triangular, UᵀU = Ω
};

// SE-Sync's term (Rosen et al., IJRR 2019, Eq. 12, in the plane):
// κ ‖R_j − R_i R_ij‖²_F + τ ‖t_j − t_i − R_i t_ij‖², with κ and τ as SE-Sync's g2o reader sets
// them (SeSyncWeights). ‖R_j − R_i R_ij‖²_F = 8 sin²(Δ/2), Δ = θ_j − θ_i − θ_ij, so the
// residual is (√τ (t_j − t_i − R_i t_ij), √(8κ) sin(Δ/2)) and Σ |r|² is SE-Sync's objective.
class RelativePoseSeSyncFactor final : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  explicit RelativePoseSeSyncFactor(const PoseGraphEdge& edge);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector2d t_ij_;
  double theta_ij_;
  double sqrt_tau_;
  double sqrt_8kappa_;
};

// SE-Sync's precisions of an edge: τ = 2 / tr(Ω_tt⁻¹) (Ω_tt the translation block of the
// information), κ = Ω_θθ.
struct SeSyncWeights {
  double kappa = 0.0;
  double tau = 0.0;
};
SeSyncWeights SeSyncWeightsOf(const PoseGraphEdge& edge);

// A prior on one pose: r = U (x ⊖ prior) with UᵀU = the information, heading wrapped.
class PosePriorFactor final : public ceres::SizedCostFunction<3, 3> {
 public:
  PosePriorFactor(const Pose2& prior, const Eigen::Matrix3d& information);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Eigen::Vector3d prior_;
  Eigen::Matrix3d sqrt_information_;
};

// The upper-triangular U with UᵀU = Ω (Ω symmetric positive definite); throws
// std::invalid_argument otherwise.
Eigen::Matrix3d SqrtInformation(const Eigen::Matrix3d& information);

}  // namespace slamkit
