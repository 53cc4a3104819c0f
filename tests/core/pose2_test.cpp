#include "slamkit/core/pose2.hpp"

#include <gtest/gtest.h>

#include "common/numeric_jacobian.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

using testing::NumericJacobian;
using testing::RandomPose;

TEST(Angle, WrapStaysInHalfOpenRange) {
  for (double a = -50.0; a < 50.0; a += 0.37) {
    const double w = WrapAngle(a);
    EXPECT_GE(w, -M_PI);
    EXPECT_LT(w, M_PI);
    EXPECT_NEAR(std::cos(w), std::cos(a), 1e-12);
    EXPECT_NEAR(std::sin(w), std::sin(a), 1e-12);
  }
  EXPECT_DOUBLE_EQ(WrapAngle(M_PI), -M_PI);
}

TEST(Pose2, ComposeWithInverseIsIdentity) {
  Rng rng(3);
  for (int i = 0; i < 50; ++i) {
    const Pose2 a = RandomPose(rng);
    const Pose2 e = a.Compose(a.Inverse());
    EXPECT_NEAR(e.x(), 0.0, 1e-12);
    EXPECT_NEAR(e.y(), 0.0, 1e-12);
    EXPECT_NEAR(e.theta(), 0.0, 1e-12);
    const Eigen::Vector2d p = testing::UniformVector2(rng, -5, 5, -5, 5);
    EXPECT_TRUE(a.TransformTo(a.TransformFrom(p)).isApprox(p, 1e-12));
  }
}

TEST(Pose2, BetweenRecoversRelativePose) {
  Rng rng(4);
  for (int i = 0; i < 50; ++i) {
    const Pose2 a = RandomPose(rng), d = RandomPose(rng);
    const Pose2 b = a.Compose(d);
    const Pose2 r = a.Between(b);
    EXPECT_NEAR(r.x(), d.x(), 1e-9);
    EXPECT_NEAR(r.y(), d.y(), 1e-9);
    EXPECT_NEAR(WrapAngle(r.theta() - d.theta()), 0.0, 1e-12);
  }
}

TEST(Pose2, JacobiansMatchCentralDifferences) {
  Rng rng(7);
  for (int i = 0; i < 100; ++i) {
    const Pose2 a = RandomPose(rng), b = RandomPose(rng);
    const Eigen::Vector2d p = testing::UniformVector2(rng, -5, 5, -5, 5);
    Eigen::Matrix3d J_a, J_b, J_inv;
    a.Compose(b, &J_a, &J_b);
    auto compose_a = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return Pose2(v).Compose(b).vector();
    };
    auto compose_b = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return a.Compose(Pose2(v)).vector();
    };
    EXPECT_TRUE(J_a.isApprox(NumericJacobian(compose_a, a.vector(), 2), 1e-6));
    EXPECT_TRUE(J_b.isApprox(NumericJacobian(compose_b, b.vector(), 2), 1e-6));

    a.Inverse(&J_inv);
    auto inverse = [](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return Pose2(v).Inverse().vector();
    };
    EXPECT_TRUE(J_inv.isApprox(NumericJacobian(inverse, a.vector(), 2), 1e-6));

    Eigen::Matrix3d J_ba, J_bb;
    a.Between(b, &J_ba, &J_bb);
    auto between_a = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return Pose2(v).Between(b).vector();
    };
    auto between_b = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return a.Between(Pose2(v)).vector();
    };
    EXPECT_TRUE(J_ba.isApprox(NumericJacobian(between_a, a.vector(), 2), 1e-6));
    EXPECT_TRUE(J_bb.isApprox(NumericJacobian(between_b, b.vector(), 2), 1e-6));

    Eigen::Matrix<double, 2, 3> J_fx, J_tx;
    Eigen::Matrix2d J_fp, J_tp;
    a.TransformFrom(p, &J_fx, &J_fp);
    a.TransformTo(p, &J_tx, &J_tp);
    auto from_x = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return Pose2(v).TransformFrom(p);
    };
    auto from_p = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return a.TransformFrom(v);
    };
    auto to_x = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return Pose2(v).TransformTo(p);
    };
    auto to_p = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return a.TransformTo(v); };
    EXPECT_TRUE(J_fx.isApprox(NumericJacobian(from_x, a.vector()), 1e-6));
    EXPECT_TRUE(J_fp.isApprox(NumericJacobian(from_p, p), 1e-6));
    EXPECT_TRUE(J_tx.isApprox(NumericJacobian(to_x, a.vector()), 1e-6));
    EXPECT_TRUE(J_tp.isApprox(NumericJacobian(to_p, p), 1e-6));
  }
}

}  // namespace
}  // namespace slamkit
