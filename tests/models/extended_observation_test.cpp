#include "slamkit/models/extended_observation.hpp"

#include <gtest/gtest.h>

#include "common/numeric_jacobian.hpp"

namespace slamkit {
namespace {

using testing::NumericJacobian;
using testing::RandomPointNear;
using testing::RandomPose;

Pose2 PoseNear(const Pose2& a, Rng& rng) {
  const Eigen::Vector2d p = RandomPointNear(a, rng);
  const double theta = rng.Uniform(-3.0, 3.0);
  return Pose2(p.x(), p.y(), theta);
}

TEST(VehicleSighting, IsTheRangeBearingOfTheOtherPositionWithItsJacobians) {
  Rng rng(3);
  for (int i = 0; i < 50; ++i) {
    const Pose2 a = RandomPose(rng);
    const Pose2 b = PoseNear(a, rng);
    Eigen::Matrix<double, 2, 3> J_a, J_b;
    const RangeBearing z = PredictVehicleSighting(a, b, &J_a, &J_b);
    EXPECT_NEAR(z.range_m, (b.translation() - a.translation()).norm(), 1e-12);
    const auto f_a = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      const RangeBearing r = PredictVehicleSighting(Pose2(v), b);
      return Eigen::Vector2d(r.range_m, r.bearing_rad);
    };
    const auto f_b = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      const RangeBearing r = PredictVehicleSighting(a, Pose2(v));
      return Eigen::Vector2d(r.range_m, r.bearing_rad);
    };
    EXPECT_TRUE(J_a.isApprox(NumericJacobian(f_a, a.vector(), 1), 1e-6));
    EXPECT_TRUE(J_b.isApprox(NumericJacobian(f_b, b.vector(), 1), 1e-6));
  }
}

// The composition is where a would see the feature: the true geometry of three points.
TEST(ExtendedObservation, IsTheFeatureAsSeenFromTheFirstVehicle) {
  Rng rng(5);
  for (int i = 0; i < 50; ++i) {
    const Pose2 a = RandomPose(rng);
    const Pose2 b = PoseNear(a, rng);
    const Eigen::Vector2d f = RandomPointNear(b, rng);
    const RangeBearing z_ab = PredictVehicleSighting(a, b);
    const RangeBearing z_bf = PredictRangeBearing(b, f);
    const RangeBearing z = ComposeExtendedObservation(z_ab, z_bf, b.theta() - a.theta());
    const RangeBearing direct = PredictRangeBearing(a, f);
    EXPECT_NEAR(z.range_m, direct.range_m, 1e-9);
    EXPECT_NEAR(WrapAngle(z.bearing_rad - direct.bearing_rad), 0.0, 1e-9);
  }
}

TEST(ExtendedObservation, JacobianMatchesNumericAndCovarianceIsItsPushForward) {
  Rng rng(9);
  for (int i = 0; i < 100; ++i) {
    Eigen::VectorXd in(5);
    in << rng.Uniform(0.5, 5000.0), rng.Uniform(-3.1, 3.1), rng.Uniform(0.5, 5000.0),
        rng.Uniform(-3.1, 3.1), rng.Uniform(-3.1, 3.1);
    ExtendedObservationJacobian J;
    ComposeExtendedObservation({in[0], in[1]}, {in[2], in[3]}, in[4], &J);
    const auto f = [](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      const RangeBearing z = ComposeExtendedObservation({v[0], v[1]}, {v[2], v[3]}, v[4]);
      return Eigen::Vector2d(z.range_m, z.bearing_rad);
    };
    const Eigen::MatrixXd numeric = NumericJacobian(f, in, 1, 1e-5);
    EXPECT_TRUE(J.isApprox(numeric, 1e-5)) << J << "\n" << numeric;
  }
  // R^e of independent inputs: J diag(R_ab, R_bf, var) Jᵀ, symmetric and positive definite.
  ExtendedObservationJacobian J;
  ComposeExtendedObservation({1000.0, 0.3}, {800.0, -1.0}, 0.4, &J);
  const Eigen::Matrix2d R = Eigen::Vector2d(25.0, 1e-4).asDiagonal();
  const Eigen::Matrix2d Re = ExtendedObservationCovariance(J, R, R, 1e-4);
  EXPECT_TRUE(Re.isApprox(Re.transpose()));
  EXPECT_GT(Re.determinant(), 0.0);
  // More uncertainty in any input never shrinks it.
  const Eigen::Matrix2d wider = ExtendedObservationCovariance(J, R, R, 1e-2);
  EXPECT_GT((wider - Re).eigenvalues().real().minCoeff(), -1e-12);
}

}  // namespace
}  // namespace slamkit
