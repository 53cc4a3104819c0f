#include "slamkit/optim/robust_loss.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"
#include "slamkit/optim/pose_graph_optimizer.hpp"

namespace slamkit::optim_test {
namespace {

// ρ' is DCS's scaling squared, ρ'' its derivative, ρ continuous at the knee; ρ' and ρ'' against
// central differences of ρ.
TEST(RobustLoss, DcsIsTheScalingOfAgarwalEtAl) {
  const DcsLoss loss(2.0);
  for (double s : {0.5, 1.9, 2.5, 10.0, 1e4}) {
    double rho[3], plus[3], minus[3];
    loss.Evaluate(s, rho);
    const double scaling = std::min(1.0, 2.0 * 2.0 / (2.0 + s));
    EXPECT_NEAR(rho[1], scaling * scaling, 1e-12) << s;
    const double h = 1e-6 * s;
    loss.Evaluate(s + h, plus);
    loss.Evaluate(s - h, minus);
    EXPECT_NEAR(rho[1], (plus[0] - minus[0]) / (2 * h), 1e-6) << s;
    EXPECT_NEAR(rho[2], (plus[1] - minus[1]) / (2 * h), 1e-6) << s;
    EXPECT_LT(rho[0], 3.0 * 2.0 + 1e-9);  // bounded by 3Φ
  }
  double below[3], above[3];
  loss.Evaluate(2.0 - 1e-12, below);
  loss.Evaluate(2.0 + 1e-12, above);
  EXPECT_NEAR(below[0], above[0], 1e-9);
  EXPECT_EQ(MakeRobustLoss({}), nullptr);
  EXPECT_THROW(MakeRobustLoss({RobustLossKind::kHuber, 0.0}), std::invalid_argument);
  EXPECT_NE(MakeRobustLoss({RobustLossKind::kCauchy, 1.0}), nullptr);
}

// A loop of 80 poses with 20 true closures measured with noise, and 10 false ones between random
// poses: without a robust loss the false closures pull the solution apart; with DCS or Cauchy on
// the closures it stays within 5 % of the clean graph's error (and far below the plain one's).
TEST(RobustLoss, FalseLoopClosuresDoNotTearTheGraph) {
  Rng rng(21);
  std::vector<Pose2> truth = {Pose2()};
  for (int i = 1; i < 80; ++i) truth.push_back(truth.back().Compose(Pose2(0.5, 0.0, 2 * M_PI / 80)));
  const Eigen::Matrix3d info = Eigen::Vector3d(2500.0, 2500.0, 1e4).asDiagonal();  // σ 2 cm, 0.01 rad
  const auto noisy = [&](int i, int j) {
    const Pose2 z = truth[i].Inverse().Compose(truth[j]);
    return Pose2(z.x() + rng.Normal(0, 0.02), z.y() + rng.Normal(0, 0.02), z.theta() + rng.Normal(0, 0.01));
  };
  PoseGraph clean;
  for (int i = 0; i < 80; ++i) clean.vertices.push_back({i, Pose2()});
  for (int i = 1; i < 80; ++i) clean.edges.push_back({i - 1, i, noisy(i - 1, i), info});
  for (int k = 0; k < 20; ++k) {
    const int i = static_cast<int>(rng.Uniform(0, 40)), j = i + 40 - static_cast<int>(rng.Uniform(0, 3));
    clean.edges.push_back({i, j, noisy(i, j), info});
  }
  PoseGraph corrupted = clean;
  for (int k = 0; k < 10; ++k) {  // between random poses, a random relative pose
    const int i = static_cast<int>(rng.Uniform(0, 80)), j = (i + 7 + static_cast<int>(rng.Uniform(0, 60))) % 80;
    corrupted.edges.push_back({i, j, Pose2(rng.Uniform(-5, 5), rng.Uniform(-5, 5), rng.Uniform(-3, 3)), info});
  }
  // From the odometry chain, as a front end starts: the chordal start is least squares too,
  // and false closures spoil it.
  std::vector<Pose2> odometry = {Pose2()};
  for (int i = 1; i < 80; ++i) odometry.push_back(odometry.back().Compose(clean.edges[i - 1].measurement));
  const auto error = [&](const PoseGraph& g, const PoseGraphOptimizerParams& p) {
    const PoseGraphSolution s = OptimizePoseGraph(g, odometry, p);
    double sum = 0.0;
    for (int i = 0; i < 80; ++i) sum += (s.poses[i].translation() - truth[i].translation()).squaredNorm();
    return std::sqrt(sum / 80);
  };
  PoseGraphOptimizerParams plain;
  const double clean_error = error(clean, plain);
  EXPECT_LT(clean_error, 0.5);
  EXPECT_GT(error(corrupted, plain), 3.0 * clean_error);
  for (const RobustLossKind kind : {RobustLossKind::kDcs, RobustLossKind::kCauchy}) {
    PoseGraphOptimizerParams robust;
    robust.loop_closure_loss = {kind, kind == RobustLossKind::kDcs ? 9.0 : 3.0};
    EXPECT_LT(error(corrupted, robust), 1.05 * error(clean, robust)) << RobustLossName(kind);
    EXPECT_LT(error(clean, robust), 1.05 * clean_error) << RobustLossName(kind);
  }
}

}  // namespace
}  // namespace slamkit::optim_test
