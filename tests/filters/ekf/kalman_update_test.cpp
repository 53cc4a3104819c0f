#include "slamkit/filters/ekf/kalman_update.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "slamkit/core/rng.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

Eigen::Matrix2d RandomSpd(Rng& rng, double scale) {
  Eigen::Matrix2d A;
  A << rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1), rng.Uniform(-1, 1);
  return scale * (A * A.transpose() + 0.1 * Eigen::Matrix2d::Identity());
}

// Against Probabilistic Robotics Table 3.3: K = P Hᵀ (H P Hᵀ + R)⁻¹, x + K ν, (I − K H) P.
TEST(KalmanUpdate, EqualsTextbookFormula) {
  Rng rng(5);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector2d x = testing::UniformVector2(rng, -5, 5, -5, 5);
    const Eigen::Matrix2d P = RandomSpd(rng, 2.0), R = RandomSpd(rng, 0.1);
    Eigen::Matrix2d H;
    H << rng.Uniform(-2, 2), rng.Uniform(-2, 2), rng.Uniform(-2, 2), rng.Uniform(-2, 2);
    const Eigen::Vector2d nu = testing::UniformVector2(rng, -1, 1, -1, 1);

    const Eigen::Matrix2d S = H * P * H.transpose() + R;
    const Eigen::Matrix2d K = P * H.transpose() * S.inverse();
    const auto out = KalmanUpdate<2, 2>(x, P, nu, H, R);
    ASSERT_TRUE(out.ok);
    EXPECT_LT((out.S - S).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_EQ(out.innovation, nu);
    EXPECT_LT((out.mean - (x + K * nu)).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_LT((out.covariance - (Eigen::Matrix2d::Identity() - K * H) * P).cwiseAbs().maxCoeff(),
              1e-10);
    EXPECT_LT((out.covariance - out.covariance.transpose()).cwiseAbs().maxCoeff(), 1e-15);
  }
}

TEST(KalmanUpdate, RectangularAndDynamicSizes) {
  Rng rng(6);
  Eigen::MatrixXd P = Eigen::Vector3d(1.0, 2.0, 0.5).asDiagonal();
  Eigen::MatrixXd H(1, 3);
  H << 1.0, -1.0, 0.5;
  Eigen::MatrixXd R(1, 1);
  R << 0.2;
  const Eigen::VectorXd x = Eigen::Vector3d(1, 2, 3), nu = Eigen::VectorXd::Constant(1, 0.3);
  const auto out = KalmanUpdate<Eigen::Dynamic, Eigen::Dynamic>(x, P, nu, H, R);
  const Eigen::MatrixXd K = P * H.transpose() / (H * P * H.transpose() + R)(0, 0);
  EXPECT_LT((out.mean - (x + K * nu)).norm(), 1e-12);
  EXPECT_LT((out.covariance - (Eigen::MatrixXd::Identity(3, 3) - K * H) * P).norm(), 1e-12);
}

TEST(KalmanUpdate, RefusesNonPositiveInnovationCovariance) {
  const Eigen::Matrix2d P = Eigen::Matrix2d::Identity(), R = -2.0 * Eigen::Matrix2d::Identity();
  const auto out = KalmanUpdate<2, 2>(Eigen::Vector2d(1, 1), P, Eigen::Vector2d(1, 0),
                                      Eigen::Matrix2d::Identity(), R);
  EXPECT_FALSE(out.ok);
  EXPECT_EQ(out.mean, Eigen::Vector2d(1, 1));
  EXPECT_EQ(out.covariance, P);
}

}  // namespace
}  // namespace slamkit
