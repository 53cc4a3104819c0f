#include "slamkit/models/motion_sampling.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "slamkit/models/car_like.hpp"

namespace slamkit {
namespace {

// With noise small enough for the model to be linear over its spread, samples must have the
// linearised prediction's mean f(x, u) and covariance J_x_u Q J_x_uᵀ. Bounds: 5 standard errors.
TEST(SampleMotion, MatchesLinearisedPredictionStatistically) {
  const CarLikeModel model({.wheelbase_m = 2.5, .sigma_v_mps = 0.05, .sigma_steer_rad = 0.01});
  const Pose2 x(1.0, 2.0, 3.1);  // near ±π: heading differences must be wrapped
  Control u(2);
  u << 2.0, 0.2;
  const double dt_s = 0.5;
  Eigen::Matrix3d J_x_x;
  ControlJacobian J_x_u;
  const Pose2 mean = model.Move(x, u, dt_s, &J_x_x, &J_x_u);
  const Eigen::Matrix3d cov = J_x_u * model.Noise(u, dt_s) * J_x_u.transpose();

  constexpr int kSamples = 20000;
  Rng rng(99);
  std::vector<Eigen::Vector3d> d(kSamples);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (auto& e : d) {
    e = PoseError(SampleMotion(model, x, u, dt_s, rng), mean);
    sum += e;
  }
  const Eigen::Vector3d sample_mean = sum / kSamples;
  Eigen::Matrix3d sample_cov = Eigen::Matrix3d::Zero();
  for (const auto& e : d) sample_cov += (e - sample_mean) * (e - sample_mean).transpose();
  sample_cov /= kSamples - 1;
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(sample_mean[i]), 5.0 * std::sqrt(cov(i, i) / kSamples)) << i;
    for (int j = 0; j < 3; ++j) {
      const double se = std::sqrt((cov(i, i) * cov(j, j) + cov(i, j) * cov(i, j)) / kSamples);
      EXPECT_LT(std::abs(sample_cov(i, j) - cov(i, j)), 5.0 * se) << i << "," << j;
    }
  }
}

TEST(SampleMotion, UsesTheGivenControlNoise) {
  const CarLikeModel model;
  Control u(2);
  u << 1.0, 0.0;
  const ControlCovariance none = ControlCovariance::Zero(2, 2);
  Rng rng(1);
  const Pose2 moved = SampleMotion(model, Pose2(), u, 1.0, rng, &none);
  EXPECT_LT((moved.vector() - model.Move(Pose2(), u, 1.0).vector()).norm(), 1e-15);
}

}  // namespace
}  // namespace slamkit
