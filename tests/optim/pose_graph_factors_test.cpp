#include "slamkit/optim/pose_graph_factors.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"
#include "numeric_jacobians.hpp"

namespace slamkit::optim_test {
namespace {

Eigen::Matrix3d RandomInformation(Rng& rng) {
  Eigen::Matrix3d A;
  for (int i = 0; i < 9; ++i) A(i / 3, i % 3) = rng.Uniform(-1.0, 1.0);
  return A * A.transpose() + 0.5 * Eigen::Matrix3d::Identity();
}

PoseGraphEdge RandomEdge(Rng& rng) {
  PoseGraphEdge e;
  e.measurement = Pose2(rng.Uniform(-3, 3), rng.Uniform(-3, 3), rng.Uniform(-3.1, 3.1));
  e.information = RandomInformation(rng);
  return e;
}

TEST(PoseGraphFactors, JacobiansMatchNumericDerivatives) {
  Rng rng(3);
  for (int trial = 0; trial < 50; ++trial) {
    const PoseGraphEdge e = RandomEdge(rng);
    Eigen::Vector3d xi(rng.Uniform(-5, 5), rng.Uniform(-5, 5), rng.Uniform(-9, 9));
    // x_j near x_i ∘ Z_ij, so the heading residual stays away from the wrap at ±π.
    Eigen::Vector3d xj = Pose2(xi).Compose(e.measurement).vector();
    xj += Eigen::Vector3d(rng.Uniform(-0.5, 0.5), rng.Uniform(-0.5, 0.5), rng.Uniform(-1, 1));
    RelativePoseChi2Factor chi2(e);
    RelativePoseSeSyncFactor sesync(e);
    PosePriorFactor prior(e.measurement, e.information);
    ExpectGradientsMatch(chi2, {xi.data(), xj.data()});
    ExpectGradientsMatch(sesync, {xi.data(), xj.data()});
    ExpectGradientsMatch(prior, {xj.data()});
  }
}

// |r|² is g2o's eᵀ Ω e with e = Z⁻¹ ∘ X_i⁻¹ ∘ X_j, and SE-Sync's κ‖R_j − R_i R_ij‖²_F +
// τ‖t_j − t_i − R_i t_ij‖², each computed here another way.
TEST(PoseGraphFactors, ResidualsAreTheTwoObjectivesTerms) {
  Rng rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const PoseGraphEdge edge = RandomEdge(rng);
    const Pose2 a(rng.Uniform(-5, 5), rng.Uniform(-5, 5), rng.Uniform(-3, 3));
    const Pose2 b(rng.Uniform(-5, 5), rng.Uniform(-5, 5), rng.Uniform(-3, 3));
    const Eigen::Vector3d xa = a.vector(), xb = b.vector();
    const double* parameters[] = {xa.data(), xb.data()};
    Eigen::Vector3d r;
    RelativePoseChi2Factor(edge).Evaluate(parameters, r.data(), nullptr);
    const Eigen::Vector3d e = edge.measurement.Inverse().Compose(a.Inverse().Compose(b)).vector();
    EXPECT_NEAR(r.squaredNorm(), e.dot(edge.information * e), 1e-9 * (1 + r.squaredNorm()));
    RelativePoseSeSyncFactor(edge).Evaluate(parameters, r.data(), nullptr);
    const SeSyncWeights w = SeSyncWeightsOf(edge);
    const Eigen::Matrix2d Ra = a.rotation(), Rb = b.rotation(), Rz = edge.measurement.rotation();
    const double expected =
        w.kappa * (Rb - Ra * Rz).squaredNorm() +
        w.tau * (b.translation() - a.translation() - Ra * edge.measurement.translation())
                    .squaredNorm();
    EXPECT_NEAR(r.squaredNorm(), expected, 1e-9 * (1 + expected));
  }
  // SE-Sync's reader: τ = 2 / tr(Ω_tt⁻¹), κ = Ω_θθ.
  PoseGraphEdge diagonal;
  diagonal.information = Eigen::Vector3d(4.0, 1.0, 9.0).asDiagonal();
  EXPECT_DOUBLE_EQ(SeSyncWeightsOf(diagonal).tau, 2.0 / 1.25);
  EXPECT_DOUBLE_EQ(SeSyncWeightsOf(diagonal).kappa, 9.0);
}

TEST(PoseGraphFactors, AnInformationThatIsNotPositiveDefiniteIsRejected) {
  PoseGraphEdge e;
  e.information(2, 2) = -1.0;
  EXPECT_THROW(RelativePoseChi2Factor{e}, std::invalid_argument);
  EXPECT_THROW(RelativePoseSeSyncFactor{e}, std::invalid_argument);
  e.information = Eigen::Matrix3d::Identity();
  e.information(0, 1) = 0.5;  // not symmetric
  EXPECT_THROW(RelativePoseChi2Factor{e}, std::invalid_argument);
}

}  // namespace
}  // namespace slamkit::optim_test
