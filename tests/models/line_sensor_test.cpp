#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "common/numeric_jacobian.hpp"
#include "slamkit/models/line_sensor.hpp"

namespace slamkit {
namespace {

using testing::NumericJacobian;
using testing::RandomPose;

Eigen::VectorXd AsVector(const PolarLine& l) { return Eigen::Vector2d(l.rho_m, l.alpha_rad); }
PolarLine AsLine(const Eigen::VectorXd& v) { return {v[0], v[1]}; }

// ρ of the line seen from `x` before any flip; the model is not differentiable where it is 0.
double RawRho(const Pose2& x, const PolarLine& l) {
  return l.rho_m - x.x() * std::cos(l.alpha_rad) - x.y() * std::sin(l.alpha_rad);
}

void ExpectLineJacobians(const Pose2& x, const PolarLine& l) {
  SCOPED_TRACE(::testing::Message() << "pose " << x.vector().transpose() << " line " << l.rho_m
                                    << ", " << l.alpha_rad);
  Eigen::Matrix<double, 2, 3> J_x;
  Eigen::Matrix2d J_l;
  const PolarLine z = PredictLine(x, l, &J_x, &J_l);
  EXPECT_GE(z.rho_m, 0.0);
  auto by_x = [&](const Eigen::VectorXd& v) { return AsVector(PredictLine(Pose2(v), l)); };
  auto by_l = [&](const Eigen::VectorXd& v) { return AsVector(PredictLine(x, AsLine(v))); };
  EXPECT_TRUE(J_x.isApprox(NumericJacobian(by_x, x.vector(), 1), 1e-6))
      << J_x << "\n" << NumericJacobian(by_x, x.vector(), 1);
  EXPECT_TRUE(J_l.isApprox(NumericJacobian(by_l, AsVector(l), 1), 1e-6))
      << J_l << "\n" << NumericJacobian(by_l, AsVector(l), 1);

  Eigen::Matrix<double, 2, 3> G_x;
  Eigen::Matrix2d G_z;
  const PolarLine back = InvertLine(x, z, &G_x, &G_z);
  EXPECT_NEAR(back.rho_m, l.rho_m, 1e-9);
  EXPECT_NEAR(WrapAngle(back.alpha_rad - l.alpha_rad), 0.0, 1e-9);
  auto inv_x = [&](const Eigen::VectorXd& v) { return AsVector(InvertLine(Pose2(v), z)); };
  auto inv_z = [&](const Eigen::VectorXd& v) { return AsVector(InvertLine(x, AsLine(v))); };
  EXPECT_TRUE(G_x.isApprox(NumericJacobian(inv_x, x.vector(), 1), 1e-6))
      << G_x << "\n" << NumericJacobian(inv_x, x.vector(), 1);
  EXPECT_TRUE(G_z.isApprox(NumericJacobian(inv_z, AsVector(z), 1), 1e-6))
      << G_z << "\n" << NumericJacobian(inv_z, AsVector(z), 1);
}

TEST(LineSensor, JacobiansMatchCentralDifferencesOnBothSidesOfTheLine) {
  Rng rng(7);
  int flipped = 0, kept = 0;
  for (int i = 0; i < 200; ++i) {
    const Pose2 x = RandomPose(rng, 8.0);
    const PolarLine l{rng.Uniform(0.0, 10.0), rng.Uniform(-3.14159, 3.14159)};
    if (std::abs(RawRho(x, l)) < 0.05) continue;  // on the line: ρ = 0, α undefined
    (RawRho(x, l) < 0.0 ? flipped : kept) += 1;
    ExpectLineJacobians(x, l);
  }
  EXPECT_GT(flipped, 30);
  EXPECT_GT(kept, 30);
}

TEST(LineSensor, AlphaNearPlusMinusPi) {
  for (const double alpha : {std::numbers::pi - 1e-4, -std::numbers::pi + 1e-4, std::numbers::pi}) {
    ExpectLineJacobians(Pose2(0.5, -0.3, 0.2), {3.0, alpha});
    ExpectLineJacobians(Pose2(1.0, 2.0, -3.1), {3.0, alpha});     // the robot's α near 0
    ExpectLineJacobians(Pose2(-1.0, 0.5, 3.14), {2.0, 0.001});    // world α near 0, robot's near ±π
  }
}

TEST(LineSensor, LineBehindTheRobotFlipsToPositiveRho) {
  // Wall x = 2 (ρ 2, α 0) seen from (5, 0) heading 0.3: the robot is beyond it, 3 m away, and the
  // wall's normal as seen from there points back along −x.
  const Pose2 x(5.0, 0.0, 0.3);
  const PolarLine l{2.0, 0.0};
  const PolarLine z = PredictLine(x, l);
  EXPECT_NEAR(z.rho_m, 3.0, 1e-12);
  EXPECT_NEAR(WrapAngle(z.alpha_rad - (std::numbers::pi - 0.3)), 0.0, 1e-12);
  ExpectLineJacobians(x, l);
  // The same wall from the origin side, and through the robot's far side as it crosses.
  ExpectLineJacobians(Pose2(1.0, 0.0, 0.3), l);
  ExpectLineJacobians(Pose2(2.1, 7.0, -1.0), l);
  ExpectLineJacobians(Pose2(1.9, -7.0, 2.0), l);
}

TEST(LineSensor, InverseFlipsWhenTheWorldOriginIsBehindTheLine) {
  // A robot at (10, 0) heading π sees a line 1 m ahead (α 0 along its own x): world x = 9, whose
  // normal from the world origin points along +x, not along the robot's heading.
  const Pose2 x(10.0, 0.0, std::numbers::pi);
  const PolarLine l = InvertLine(x, {1.0, 0.0});
  EXPECT_NEAR(l.rho_m, 9.0, 1e-12);
  EXPECT_NEAR(WrapAngle(l.alpha_rad), 0.0, 1e-12);
  ExpectLineJacobians(x, l);
}

TEST(LineSensor, WrapLineAngleMapsMinusPiToPi) {
  EXPECT_DOUBLE_EQ(WrapLineAngle(-std::numbers::pi), std::numbers::pi);
  EXPECT_DOUBLE_EQ(WrapLineAngle(3.0 * std::numbers::pi), std::numbers::pi);
  EXPECT_NEAR(WrapLineAngle(-std::numbers::pi + 1e-9), -std::numbers::pi + 1e-9, 1e-15);
  PolarLine l{-2.0, 0.5};
  EXPECT_TRUE(NormaliseLine(&l));
  EXPECT_NEAR(l.rho_m, 2.0, 1e-15);
  EXPECT_NEAR(l.alpha_rad, 0.5 - std::numbers::pi, 1e-15);
}

TEST(LineSensor, MahalanobisWrapsTheAngle) {
  Eigen::Matrix2d S;
  S << 0.01, 0.0, 0.0, 0.0004;
  // Δρ = 0.1 (1 σ), Δα = −0.02 across ±π (1 σ): d² = 2.
  const PolarLine z{2.1, std::numbers::pi - 0.01}, z_pred{2.0, -std::numbers::pi + 0.01};
  EXPECT_NEAR(LineMahalanobis2(z, z_pred, S), 2.0, 1e-9);
  const Eigen::Vector2d nu = LineInnovation(z, z_pred);
  EXPECT_NEAR(nu[1], -0.02, 1e-12);
}

TEST(PointSegmentDistance, PerpendicularInsideAndToTheNearerEndOutside) {
  const Eigen::Vector2d a(0, 1), b(4, 1);
  EXPECT_NEAR(PointSegmentDistanceSq({2, 3}, a, b), 4.0, 1e-12);   // foot inside: 2 m across
  EXPECT_NEAR(PointSegmentDistanceSq({7, 5}, a, b), 25.0, 1e-12);  // beyond b: 3-4-5 to b
  EXPECT_NEAR(PointSegmentDistanceSq({-1, 1}, b, a), 1.0, 1e-12);  // before a, either order
  EXPECT_NEAR(PointSegmentDistanceSq({3, 5}, a, a), 25.0, 1e-12);  // a point segment
}

TEST(SegmentOverlap, CollinearWallsFarApartDoNotOverlap) {
  const double alpha = std::numbers::pi / 2.0;  // both on the line y = 1
  const Eigen::Vector2d a1(0, 1), b1(3, 1);
  EXPECT_NEAR(SegmentOverlapM(a1, b1, {2, 1}, {6, 1}, alpha), 1.0, 1e-12);
  EXPECT_NEAR(SegmentOverlapM(b1, a1, {6, 1}, {2, 1}, alpha), 1.0, 1e-12);  // either end order
  EXPECT_TRUE(SegmentsOverlap(a1, b1, {2, 1}, {6, 1}, alpha));
  EXPECT_TRUE(SegmentsOverlap(a1, b1, {1, 1.02}, {2, 0.98}, alpha, 0.5));   // contained
  // The same (ρ, α), 5 m apart: no overlap, and a 5 m gap.
  EXPECT_NEAR(SegmentOverlapM(a1, b1, {8, 1}, {10, 1}, alpha), -5.0, 1e-12);
  EXPECT_FALSE(SegmentsOverlap(a1, b1, {8, 1}, {10, 1}, alpha));
  EXPECT_FALSE(SegmentsOverlap(a1, b1, {8, 1}, {10, 1}, alpha, -4.0));
  EXPECT_TRUE(SegmentsOverlap(a1, b1, {8, 1}, {10, 1}, alpha, -5.5));
}

}  // namespace
}  // namespace slamkit
