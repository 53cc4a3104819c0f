#include "slamkit/filters/selection.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>

#include "filters/dense_reference.hpp"
#include "slamkit/filters/ekf_slam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

// A direct fix of one point block, z = l: S_i is that block's covariance plus R.
class PointFixModel final : public ObservationModel {
 public:
  int MeasurementDim() const override { return 2; }
  BlockPrediction Predict(const BlockEkf& ekf, std::span<const int> blocks) const override {
    BlockPrediction p;
    p.z = ekf.Mean(blocks[0]);
    p.J_z_blocks.Add(blocks[0], Eigen::Matrix2d::Identity());
    return p;
  }
  BlockVector Innovation(const BlockVector& z, const BlockVector& z_pred) const override {
    return z - z_pred;
  }
};

// A test policy of the shape of SPEC S1 Algorithm 3 (not that policy): greedy by |S_i| / |R_i|
// with a budget, re-ranking from the session's recomputed S after every applied update.
class GreedyBySensitivity final : public SelectionPolicy {
 public:
  explicit GreedyBySensitivity(int k_max) : k_max_(k_max) {}
  void Select(SelectionSession& session) override {
    for (int step = 0; step < std::min(k_max_, session.size()); ++step) {
      std::vector<int> order;
      for (int i = 0; i < session.size(); ++i) {
        if (!session.applied(i)) order.push_back(i);
      }
      std::ranges::stable_sort(
          order, [&](int a, int b) { return Sensitivity(session, a) > Sensitivity(session, b); });
      rankings.push_back(order);
      session.Apply(order.front());
      applied.push_back(order.front());
    }
  }
  static double Sensitivity(const SelectionSession& s, int i) {
    return s.S(i).determinant() / s.R(i).determinant();
  }
  std::vector<std::vector<int>> rankings;
  std::vector<int> applied;

 private:
  int k_max_;
};

TEST(Selection, ReRankingPolicyFollowsTheRecomputedInnovationCovariance) {
  BlockEkf ekf;
  const int point = ekf.RegisterKind({2, {}, false});
  const PointFixModel fix;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  // l_0 and l_1 strongly correlated (l_1 = l_0 + a small offset), l_2 independent.
  const int l0 = ekf.AddBlock(point, Eigen::Vector2d(1, 2), 4.0 * I);
  const BlockJacobian from_l0{l0, I};
  const int l1 = ekf.Augment(point, Eigen::Vector2d(1.5, 2.0), std::span(&from_l0, 1), I, 0.1 * I);
  const int l2 = ekf.AddBlock(point, Eigen::Vector2d(-3, 0), 3.0 * I);
  testing::DenseEkf ref{ekf.State(), ekf.Covariance(), {}};

  const Eigen::Matrix2d R = 0.01 * I;
  const std::vector<Eigen::Vector2d> z = {{1.2, 2.1}, {1.4, 2.3}, {-2.9, 0.2}};
  std::vector<MatchedObservation> matched;
  for (int i = 0; i < 3; ++i) {
    matched.push_back({&fix, {std::array{l0, l1, l2}[i]}, 1, z[i], R});
  }
  BlockSelectionSession session(ekf, matched);
  const Eigen::Matrix2d S0_before = session.S(0);
  GreedyBySensitivity policy(2);
  policy.Select(session);

  // Initially l_1 (largest variance) ranks first, then l_0, then l_2.
  ASSERT_EQ(policy.rankings.size(), 2u);
  EXPECT_EQ(policy.rankings[0], (std::vector<int>{1, 0, 2}));
  // Its update shrinks the correlated l_0 below l_2: the recomputed ranking differs.
  EXPECT_EQ(policy.rankings[1], (std::vector<int>{2, 0}));
  EXPECT_EQ(policy.applied, (std::vector<int>{1, 2}));
  EXPECT_FALSE(session.applied(0));
  // S(0) is now the posterior one: P_00 − P_01 (P_11 + R)⁻¹ P_10 + R.
  const Eigen::Matrix2d expected_S0 = 4.0 * I - 16.0 * I / 4.11 + R;
  EXPECT_LT((session.S(0) - expected_S0).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(S0_before.determinant(), 100.0 * session.S(0).determinant());

  // The filter holds the sequential EKF of the applied observations, in the applied order.
  for (const int i : policy.applied) {
    ref.Update(z[i] - ref.x.segment<2>(2 * i), ref.Spread(I, 2 * i), R);
  }
  ekf.ApplyPendingDowndate();
  EXPECT_LT(testing::MaxAbsDiff(ekf.State(), ref.x), 1e-12);
  EXPECT_LT(testing::MaxAbsDiff(ekf.Covariance(), ref.P), 1e-12);
}

// A policy that applies nothing: EkfSlam still adds new landmarks (SPEC S1 item 3).
class SelectNone final : public SelectionPolicy {
 public:
  void Select(SelectionSession& session) override { offered += session.size(); }
  int offered = 0;
};

TEST(Selection, EkfSlamRunsTheInjectedPolicyOnTheWholeScan) {
  EkfSlamParams params;
  params.association_method = AssociationMethod::kKnown;
  params.schedule = UpdateSchedule::kPerScan;
  auto policy = std::make_unique<SelectNone>();
  SelectNone* none = policy.get();
  EkfSlam slam(params, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>(),
               nullptr, std::move(policy));
  PointObservation a, b;
  a.z << 5.0, 0.3;
  a.id = 1;
  b.z << 8.0, -1.0;
  b.id = 2;
  slam.Update(std::vector{a});
  const Eigen::VectorXd before = slam.State();
  a.z << 5.2, 0.31;
  const auto decisions = slam.Update(std::vector{a, b});
  EXPECT_EQ(none->offered, 1);
  EXPECT_EQ(decisions[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(decisions[1].kind, AssociationDecision::Kind::kNew);
  EXPECT_EQ(slam.NumLandmarks(), 2);
  EXPECT_EQ(slam.State().head(before.size()), before);  // the match was not applied
}

}  // namespace
}  // namespace slamkit
