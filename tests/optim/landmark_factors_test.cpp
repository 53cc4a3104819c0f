#include "slamkit/optim/landmark_factors.hpp"

#include <vector>

#include <gtest/gtest.h>

#include "slamkit/core/angle.hpp"
#include "slamkit/core/rng.hpp"
#include "numeric_jacobians.hpp"

namespace slamkit::optim_test {
namespace {

TEST(LandmarkFactors, JacobiansMatchNumericOnesAndResidualsAreWhitened) {
  Rng rng(9);
  for (int trial = 0; trial < 30; ++trial) {
    Eigen::Matrix3d A3 = Eigen::Matrix3d::Random();
    const Eigen::Matrix3d cov3 = A3 * A3.transpose() + 0.1 * Eigen::Matrix3d::Identity();
    Eigen::Vector3d xi(rng.Uniform(-5, 5), rng.Uniform(-5, 5), rng.Uniform(-3, 3));
    Eigen::Vector3d xj(rng.Uniform(-5, 5), rng.Uniform(-5, 5), rng.Uniform(-3, 3));
    const Pose2 delta = Pose2(xi).Between(Pose2(xj)).Compose(Pose2(0.1, -0.1, 0.2));
    const OdometryDeltaFactor odometry(delta, cov3);
    ExpectGradientsMatch(odometry, {xi.data(), xj.data()});
    const double* p2[] = {xi.data(), xj.data()};
    Eigen::Vector3d r;
    odometry.Evaluate(p2, r.data(), nullptr);
    Eigen::Vector3d e = Pose2(xi).Between(Pose2(xj)).vector() - delta.vector();
    e.z() = WrapAngle(e.z());
    EXPECT_NEAR(r.squaredNorm(), e.dot(cov3.inverse() * e), 1e-8 * (1 + r.squaredNorm()));

    Eigen::Matrix2d A2 = Eigen::Matrix2d::Random();
    const Eigen::Matrix2d cov2 = A2 * A2.transpose() + 0.1 * Eigen::Matrix2d::Identity();
    Eigen::Vector2d l(rng.Uniform(-9, 9), rng.Uniform(-9, 9));
    const Eigen::Vector2d z(rng.Uniform(-3, 3), rng.Uniform(-3, 3));
    const PosePointFactor sighting(z, cov2);
    ExpectGradientsMatch(sighting, {xi.data(), l.data()});
    const double* pl[] = {xi.data(), l.data()};
    Eigen::Vector2d rs;
    sighting.Evaluate(pl, rs.data(), nullptr);
    const Eigen::Vector2d es = Pose2(xi).TransformTo(l) - z;
    EXPECT_NEAR(rs.squaredNorm(), es.dot(cov2.inverse() * es), 1e-8 * (1 + rs.squaredNorm()));
  }
  EXPECT_THROW(PosePointFactor(Eigen::Vector2d::Zero(), -Eigen::Matrix2d::Identity()),
               std::invalid_argument);
}

}  // namespace
}  // namespace slamkit::optim_test
