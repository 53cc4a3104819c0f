#include "slamkit/optim/pose_graph_optimizer.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"

namespace slamkit::optim_test {
namespace {

constexpr double kPi = std::numbers::pi;

// A unit square driven counter-clockwise: four edges of (1, 0, π/2), the last closing the loop.
// The measured translations carry `misclosure` in all (spread over the four in world frame), the
// headings are exact and held by a large κ.
PoseGraph Square(const Eigen::Vector2d& misclosure) {
  PoseGraph g;
  for (int i = 0; i < 4; ++i) g.vertices.push_back({i * 10, Pose2(0, 0, 0)});
  for (int i = 0; i < 4; ++i) {
    PoseGraphEdge e;
    e.from = i * 10;
    e.to = ((i + 1) % 4) * 10;
    // In vertex i's frame (heading iπ/2), a world offset d is R(-iπ/2) d.
    const Eigen::Vector2d offset = Eigen::Rotation2Dd(-i * kPi / 2).toRotationMatrix() * misclosure;
    e.measurement = Pose2(1.0 + offset.x(), offset.y(), kPi / 2);
    e.information = Eigen::Vector3d(2.0, 2.0, 1e8).asDiagonal();
    g.edges.push_back(e);
  }
  return g;
}

// With the headings fixed the problem is linear: the optimum spreads the loop's misclosure
// 4 m over the four edges equally, each edge's residual m (world frame), χ² = 4 · 2 |m|²
// where 4 m = the sum of the measured world translations = 4 · misclosure.
TEST(PoseGraphOptimizer, ASquareLoopReachesItsAnalyticOptimum) {
  const Eigen::Vector2d misclosure(0.03, -0.02);
  const PoseGraph g = Square(misclosure);
  for (const PoseGraphObjective objective : {PoseGraphObjective::kChi2, PoseGraphObjective::kSeSync}) {
    PoseGraphOptimizerParams p;
    p.objective = objective;
    // From the chordal start: the file's (every pose at the origin) is far off in heading.
    const PoseGraphSolution s = OptimizePoseGraph(g, ChordalInitialization(g), p);
    ASSERT_EQ(s.poses.size(), 4u);
    EXPECT_TRUE(s.converged) << s.termination;
    EXPECT_NEAR(s.chi2, 4 * 2.0 * misclosure.squaredNorm(), 1e-6);
    // SE-Sync's τ = 2 / tr(Ω_tt⁻¹) = 2 for Ω_tt = 2 I.
    EXPECT_NEAR(s.sesync_objective, 4 * 2.0 * misclosure.squaredNorm(), 1e-6);
    // Vertex 0 is the gauge; vertex 1 lies at (1, 0) + misclosure − m = (1, 0).
    EXPECT_EQ(s.poses[0].vector(), Pose2(0, 0, 0).vector());
    EXPECT_NEAR((s.poses[1].translation() - Eigen::Vector2d(1, 0)).norm(), 0, 1e-6);
    EXPECT_NEAR((s.poses[2].translation() - Eigen::Vector2d(1, 1)).norm(), 0, 1e-6);
    EXPECT_NEAR(std::abs(s.poses[2].theta()), kPi, 1e-6);
    EXPECT_GT(s.initial_chi2, s.chi2);
    EXPECT_GT(Chi2(g, InitialPoses(g)), 1e6);
  }
}

// A random walk with loop closures, measured without noise: the chordal start is the truth
// (up to rounding), and Levenberg-Marquardt from a perturbed start gets back to χ² = 0.
TEST(PoseGraphOptimizer, ANoiseFreeGraphIsRecoveredFromChordalAndPerturbedStarts) {
  Rng rng(11);
  std::vector<Pose2> truth = {Pose2(1.0, -2.0, 0.3)};
  for (int i = 1; i < 60; ++i) {
    truth.push_back(truth.back().Compose(Pose2(rng.Uniform(0.2, 1.0), rng.Uniform(-0.2, 0.2),
                                               rng.Uniform(-1.0, 1.0))));
  }
  PoseGraph g;
  for (int i = 0; i < 60; ++i) {
    const Pose2 noisy(truth[i].x() + rng.Normal(0, 0.3), truth[i].y() + rng.Normal(0, 0.3),
                      truth[i].theta() + rng.Normal(0, 0.2));
    g.vertices.push_back({i, i == 0 ? truth[0] : noisy});
  }
  const auto add = [&](int i, int j) {
    g.edges.push_back({i, j, truth[i].Inverse().Compose(truth[j]),
                       Eigen::Vector3d(10.0, 10.0, 50.0).asDiagonal()});
  };
  for (int i = 1; i < 60; ++i) add(i - 1, i);
  for (int k = 0; k < 15; ++k) add(static_cast<int>(rng.Uniform(0, 30)), static_cast<int>(rng.Uniform(30, 60)));
  const std::vector<Pose2> chordal = ChordalInitialization(g);
  for (int i = 0; i < 60; ++i) {
    EXPECT_NEAR((chordal[i].vector() - truth[i].vector()).norm(), 0.0, 1e-9) << i;
  }
  EXPECT_GT(Chi2(g, InitialPoses(g)), 100.0);
  const PoseGraphSolution s = OptimizePoseGraph(g, InitialPoses(g));
  EXPECT_LT(s.chi2, 1e-12);
  EXPECT_LT(SeSyncObjective(g, s.poses), 1e-12);
  for (int i = 0; i < 60; ++i) {
    EXPECT_NEAR((s.poses[i].vector() - truth[i].vector()).norm(), 0.0, 1e-6) << i;
  }
}

// A chain x0 (fixed) → x1 → x2: x1's covariance is the first edge's Ω⁻¹ carried into the world
// frame by R_0 and R_01 (e = R_01ᵀ (R_0ᵀ (t_1 − t_0) − t_01) ...), and x2's is larger.
TEST(PoseGraphOptimizer, MarginalCovariancesOfAChain) {
  PoseGraph g;
  g.vertices = {{0, Pose2(1.0, 2.0, 0.4)}, {1, Pose2()}, {2, Pose2()}};
  Eigen::Matrix3d info;
  info << 40, 5, 2, 5, 20, 1, 2, 1, 80;
  g.edges = {{0, 1, Pose2(1.0, 0.2, 0.3), info}, {1, 2, Pose2(0.5, -0.1, -0.2), info}};
  std::vector<Pose2> poses = {g.vertices[0].pose};
  poses.push_back(poses[0].Compose(g.edges[0].measurement));
  poses.push_back(poses[1].Compose(g.edges[1].measurement));
  const std::vector<Eigen::Matrix3d> C = MarginalCovariances(g, poses, {0, 1, 2});
  ASSERT_EQ(C.size(), 3u);
  EXPECT_EQ(C[0], Eigen::Matrix3d::Zero());
  Eigen::Matrix3d J = Eigen::Matrix3d::Identity();  // ∂e/∂x1 = blockdiag(R_01ᵀ R_0ᵀ, 1)
  J.topLeftCorner<2, 2>() =
      (poses[0].rotation() * g.edges[0].measurement.rotation()).transpose();
  const Eigen::Matrix3d expected = J.inverse() * info.inverse() * J.inverse().transpose();
  EXPECT_LT((C[1] - expected).norm(), 1e-9 * expected.norm());
  EXPECT_GT(C[2].trace(), C[1].trace());
  g.vertices.push_back({3, Pose2()});  // reached by no edge
  poses.push_back(Pose2());
  EXPECT_THROW(MarginalCovariances(g, poses, {3}), std::invalid_argument);
}

TEST(PoseGraphOptimizer, BadGraphsAreRejected) {
  PoseGraph g = Square({0, 0});
  EXPECT_THROW(OptimizePoseGraph(g, {Pose2()}), std::invalid_argument);  // one pose for four
  g.edges[1].to = 99;
  EXPECT_THROW(OptimizePoseGraph(g, InitialPoses(g)), std::invalid_argument);
  EXPECT_THROW(ChordalInitialization(g), std::invalid_argument);
  g.edges.resize(1);  // vertices 20 and 30 are not connected
  g.edges[0].to = 10;
  EXPECT_THROW(ChordalInitialization(g), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit::optim_test
