#include "slamkit/filters/selection/selection.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>

#include "filters/dense_reference.hpp"
#include "filters/selection_fixtures.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/filters/selection/selection_policies.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

using testing::PointFixModel;

// SPEC S1, Algorithm 3: SelectByCovariance ranks by |S_i| / |R_i| against the posterior the
// previous choices left, so its second choice is not the second of the initial ranking.
TEST(Selection, CovariancePolicyReRanksAfterEachUpdate) {
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
  BlockSelectionSession inner(ekf, matched);
  testing::RecordingSession session(inner);
  const Eigen::Matrix2d S0_before = session.S(0);
  SelectByCovariance({.k_max = 2}).Select(session);

  // Initially l_1 (largest variance) ranks first, then l_0, then l_2: a ranking computed once
  // would apply {1, 0}.
  ASSERT_EQ(session.order, (std::vector<int>{1, 2}));
  const std::vector<double>& first = session.scores_at_apply[0];
  EXPECT_GT(first[1], first[0]);
  EXPECT_GT(first[0], first[2]);
  // l_1's update shrinks the correlated l_0 below l_2: the recomputed ranking differs.
  EXPECT_GT(session.scores_at_apply[1][2], session.scores_at_apply[1][0]);
  EXPECT_FALSE(session.applied(0));
  // S(0) is now the posterior one: P_00 − P_01 (P_11 + R)⁻¹ P_10 + R.
  const Eigen::Matrix2d expected_S0 = 4.0 * I - 16.0 * I / 4.11 + R;
  EXPECT_LT((session.S(0) - expected_S0).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(S0_before.determinant(), 100.0 * session.S(0).determinant());

  // The filter holds the sequential EKF of the applied observations, in the applied order.
  for (const int i : session.order) {
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

// SPEC S1 item 3: ln|P⁺| − ln|P⁻| of one update, from dense determinants of the full covariance
// (the textbook Joseph-form update), equals ln|R| − ln|S| from the small S block; and the
// session's dense LogDetAfter() − LogDetCovariance() is that difference too, also while earlier
// updates of the step are still a pending downdate.
TEST(Selection, SylvesterIdentityMatchesDenseDeterminants) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    testing::RandomSlamState state(5, seed);
    std::vector<MatchedObservation> sightings = state.Sightings();
    BlockSelectionSession session(state.ekf, sightings);
    for (int i = 0; i < session.size(); ++i) {
      const MatchedObservation& o = sightings[i];
      const Linearisation lin = Linearise(*o.model, state.ekf, o.block_view(), o.z, o.R);
      testing::DenseEkf dense{state.ekf.State(), state.ekf.Covariance(), {}};
      Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, dense.x.size());
      for (const BlockJacobian& h : lin.H.view()) {
        H.middleCols(state.ekf.BlockOffset(h.block), h.J.cols()) = h.J;
      }
      const double before = testing::DenseLogDet(dense.P);
      dense.Update(Eigen::VectorXd(lin.innovation), H, Eigen::MatrixXd(lin.R));
      const double dense_change = testing::DenseLogDet(dense.P) - before;
      const double sylvester = -LogSensitivity(session, i);
      EXPECT_NEAR(dense_change, sylvester, 1e-9) << "seed " << seed << ", observation " << i;
      EXPECT_NEAR(session.LogDetAfter(i) - session.LogDetCovariance(), sylvester, 1e-9);
      EXPECT_LT(sylvester, -1e-3);  // the identity is tested on updates that shrink |P|
      if (i % 2 == 0) session.Apply(i);  // later observations see a pending downdate
    }
    ASSERT_TRUE(state.ekf.HasPendingDowndate());
  }
}

// The session's record of a step: the applied updates' log-ratios sum to the dense log-det
// change, and with diagnostics the accuracy of SPEC S1 Eq. 24 is the dense-determinant ratio.
TEST(Selection, AccuracyRatioIsTheDenseLogDeterminantShare) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    testing::RandomSlamState state(8, seed);
    const std::vector<MatchedObservation> sightings = state.Sightings();
    const double prior = testing::DenseLogDet(state.ekf.Covariance());
    BlockEkf all_ekf = state.ekf;
    BlockSelectionSession all(all_ekf, sightings, true);
    SelectAll().Select(all);
    const double all_change = testing::DenseLogDet(all_ekf.Covariance()) - prior;
    ASSERT_TRUE(all.stats().accuracy());
    // The denominator runs on the matched blocks' marginal, the numerator on the whole filter:
    // the same updates, rounded differently.
    EXPECT_NEAR(*all.stats().accuracy(), 1.0, 1e-12);
    EXPECT_EQ(all.stats().applied, 8);
    EXPECT_NEAR(all.stats().selected_log_ratio, all_change, 1e-9);

    BlockSelectionSession some(state.ekf, sightings, true);
    SelectByCovariance({.k_max = 3}).Select(some);
    const SelectionStats& stats = some.stats();
    const double some_change = testing::DenseLogDet(state.ekf.Covariance()) - prior;
    EXPECT_EQ(stats.candidates, 8);
    EXPECT_EQ(stats.applied, 3);
    EXPECT_NEAR(stats.selected_log_ratio, some_change, 1e-9);
    ASSERT_TRUE(stats.accuracy());
    EXPECT_NEAR(*stats.all_log_ratio, all_change, 1e-9);
    EXPECT_NEAR(*stats.accuracy(), some_change / all_change, 1e-9);
    EXPECT_GT(*stats.accuracy(), 0.0);
    EXPECT_LT(*stats.accuracy(), 1.0 - 1e-6);
  }
  // Without diagnostics nothing runs on a copy, and there is no accuracy.
  testing::RandomSlamState state(3, 99);
  BlockSelectionSession session(state.ekf, state.Sightings());
  SelectAll().Select(session);
  EXPECT_FALSE(session.stats().all_log_ratio);
  EXPECT_FALSE(session.stats().accuracy());
  EXPECT_LT(session.stats().selected_log_ratio, 0.0);
}

}  // namespace
}  // namespace slamkit
