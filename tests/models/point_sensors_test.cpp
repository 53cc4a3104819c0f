#include <gtest/gtest.h>

#include "common/numeric_jacobian.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/relative_point.hpp"

namespace slamkit {
namespace {

using testing::NumericJacobian;
using testing::RandomPointNear;
using testing::RandomPose;

void ExpectSensorJacobians(const PointSensorModel& model, int angle_row) {
  Rng rng(7);
  for (int i = 0; i < 100; ++i) {
    const Pose2 x = RandomPose(rng);
    const Eigen::Vector2d l = RandomPointNear(x, rng);
    Eigen::Matrix<double, 2, 3> J_x;
    Eigen::Matrix2d J_l;
    const Eigen::Vector2d z = model.Predict(x, l, &J_x, &J_l);
    auto by_x = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return model.Predict(Pose2(v), l);
    };
    auto by_l = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return model.Predict(x, v); };
    EXPECT_TRUE(J_x.isApprox(NumericJacobian(by_x, x.vector(), angle_row), 1e-6));
    EXPECT_TRUE(J_l.isApprox(NumericJacobian(by_l, l, angle_row), 1e-6));

    Eigen::Matrix<double, 2, 3> G_x;
    Eigen::Matrix2d G_z;
    EXPECT_TRUE(model.Invert(x, z, &G_x, &G_z).isApprox(l, 1e-9));
    auto inv_x = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return model.Invert(Pose2(v), z);
    };
    auto inv_z = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return model.Invert(x, v); };
    EXPECT_TRUE(G_x.isApprox(NumericJacobian(inv_x, x.vector()), 1e-6));
    EXPECT_TRUE(G_z.isApprox(NumericJacobian(inv_z, z), 1e-6));
  }
}

TEST(RangeBearing, JacobiansMatchCentralDifferences) {
  ExpectSensorJacobians(RangeBearingModel(), 1);
}

TEST(RelativePoint, JacobiansMatchCentralDifferences) {
  ExpectSensorJacobians(RelativePointModel(), -1);
}

// Ahead on the x axis the range error is along x and the bearing error along y, scaled by the
// range; the covariance turns with the sighting's bearing.
TEST(RangeBearingCovariance, IsTheRangeAndBearingNoiseInCartesianAxes) {
  const Eigen::Matrix2d ahead = RangeBearingCovariance({10.0, 0.0}, 0.1, 0.01);
  EXPECT_NEAR(ahead(0, 0), 0.01, 1e-12);
  EXPECT_NEAR(ahead(1, 1), 0.01, 1e-12);  // (10 m × 0.01 rad)²
  EXPECT_NEAR(ahead(0, 1), 0.0, 1e-12);
  const Eigen::Matrix2d left = RangeBearingCovariance({0.0, 4.0}, 0.1, 0.01);
  EXPECT_NEAR(left(1, 1), 0.01, 1e-12);
  EXPECT_NEAR(left(0, 0), 0.0016, 1e-12);  // (4 m × 0.01 rad)²
  const Eigen::Matrix2d diagonal = RangeBearingCovariance({3.0, 3.0}, 0.1, 0.0);
  EXPECT_NEAR(diagonal(0, 1), 0.005, 1e-12);  // all along the ray: σ_r² cos b sin b
}

TEST(RangeBearing, InnovationWrapsBearing) {
  const RangeBearingModel model;
  const Eigen::Vector2d nu = model.Innovation({5.0, M_PI - 0.01}, {4.0, -M_PI + 0.01});
  EXPECT_NEAR(nu[0], 1.0, 1e-12);
  EXPECT_NEAR(nu[1], -0.02, 1e-12);
}

TEST(RangeBearing, VisibilityRespectsRangeAndFieldOfView) {
  RangeBearingParams p;
  p.max_range_m = 10.0;
  p.min_range_m = 0.5;
  p.fov_rad = M_PI;  // ±90°
  const RangeBearingModel model(p);
  const Pose2 x(0.0, 0.0, M_PI / 2);  // facing +y
  EXPECT_TRUE(model.IsVisible(x, {0.0, 9.9}));
  EXPECT_FALSE(model.IsVisible(x, {0.0, 10.1}));
  EXPECT_FALSE(model.IsVisible(x, {0.0, 0.4}));
  EXPECT_TRUE(model.IsVisible(x, {5.0, 0.01}));
  EXPECT_FALSE(model.IsVisible(x, {5.0, -0.01}));
  EXPECT_FALSE(model.IsVisible(x, {0.0, -3.0}));
}

}  // namespace
}  // namespace slamkit
