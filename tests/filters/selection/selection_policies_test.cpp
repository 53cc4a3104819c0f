// The selection policies of SPEC S1: covariance sensitivity (item 3, Algorithm 3) and entropy
// (item 2, dense as the seed specifies, and through Sylvester's identity).

#include "slamkit/filters/selection/selection_policies.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "filters/dense_reference.hpp"
#include "filters/selection_fixtures.hpp"

namespace slamkit {
namespace {

using testing::RandomSlamState;
using testing::RecordingSession;

TEST(SelectByCovariance, AppliesAtMostKMaxOfTheMatched) {
  RandomSlamState state(5, 3);
  const std::vector<MatchedObservation> sightings = state.Sightings();
  for (int k_max = 0; k_max <= 7; ++k_max) {
    BlockEkf ekf = state.ekf;
    BlockSelectionSession session(ekf, sightings);
    SelectByCovariance({.k_max = k_max}).Select(session);
    int applied = 0;
    for (int i = 0; i < session.size(); ++i) applied += session.applied(i) ? 1 : 0;
    EXPECT_EQ(applied, std::min(k_max, 5)) << "k_max " << k_max;
    EXPECT_EQ(session.stats().applied, applied);
  }
  EXPECT_THROW(SelectByCovariance({.k_max = -1}), std::invalid_argument);
}

// Each choice is the unapplied observation of largest ln|S_i| − ln|R_i| at that moment.
TEST(SelectByCovariance, EachChoiceIsTheMostSensitiveAgainstTheCurrentPosterior) {
  int re_ranked = 0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    RandomSlamState state(8, seed);
    BlockSelectionSession inner(state.ekf, state.Sightings());
    RecordingSession session(inner);
    SelectByCovariance({.k_max = 4}).Select(session);
    ASSERT_EQ(session.order.size(), 4u);
    for (std::size_t k = 0; k < session.order.size(); ++k) {
      const std::vector<double>& scores = session.scores_at_apply[k];
      const auto best = std::ranges::max_element(scores) - scores.begin();
      EXPECT_EQ(session.order[k], best) << "seed " << seed << ", choice " << k;
    }
    // Whether a ranking computed once, from the prior, would have chosen differently.
    std::vector<int> by_prior(8);
    for (int i = 0; i < 8; ++i) by_prior[i] = i;
    const std::vector<double>& prior = session.scores_at_apply[0];
    std::ranges::stable_sort(by_prior, [&](int a, int b) { return prior[a] > prior[b]; });
    by_prior.resize(4);
    re_ranked += by_prior != session.order ? 1 : 0;
  }
  EXPECT_GT(re_ranked, 0);  // the correlations of these states make re-ranking matter
}

TEST(SelectByCovariance, BudgetAtLeastTheMatchedIsTheSequentialEkf) {
  for (const int k_max : {6, 20}) {
    RandomSlamState state(6, 5);
    const std::vector<MatchedObservation> sightings = state.Sightings();
    BlockEkf all = state.ekf;
    BlockSelectionSession all_session(all, sightings);
    SelectAll().Select(all_session);
    BlockSelectionSession session(state.ekf, sightings);
    SelectByCovariance({.k_max = k_max}).Select(session);
    all.ApplyPendingDowndate();
    state.ekf.ApplyPendingDowndate();
    EXPECT_LT(testing::MaxAbsDiff(state.ekf.State(), all.State()), 1e-9);
    EXPECT_LT(testing::MaxAbsDiff(state.ekf.Covariance(), all.Covariance()), 1e-9);
  }
}

// Two independent landmarks, one already known to 1 cm and one to 1 m: the first update gains
// ½·2·ln(1.01) ≈ 0.00995 nats, the second ½·2·ln(101) ≈ 4.6 nats.
template <typename Policy>
std::vector<bool> AppliedByEntropy(double min_gain_nats, double* gain_0 = nullptr) {
  BlockEkf ekf;
  const int point = ekf.RegisterKind({2, {}, false});
  const testing::PointFixModel fix;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  const int known = ekf.AddBlock(point, Eigen::Vector2d(1, 2), 1e-4 * I);
  const int vague = ekf.AddBlock(point, Eigen::Vector2d(-3, 0), 1.0 * I);
  std::vector<MatchedObservation> matched = {
      {&fix, {known}, 1, Eigen::Vector2d(1.01, 2.0), 0.01 * I},
      {&fix, {vague}, 1, Eigen::Vector2d(-2.5, 0.3), 0.01 * I}};
  BlockSelectionSession session(ekf, matched);
  if (gain_0 != nullptr) *gain_0 = DenseInformationGain(session, 0);
  Policy({.min_gain_nats = min_gain_nats}).Select(session);
  return {session.applied(0), session.applied(1)};
}

template <typename Policy>
void ExpectThresholdBehaviour() {
  double gain_0 = 0.0;
  EXPECT_EQ(AppliedByEntropy<Policy>(0.05, &gain_0), (std::vector<bool>{false, true}));
  EXPECT_NEAR(gain_0, std::log(1.01), 1e-12);
  EXPECT_EQ(AppliedByEntropy<Policy>(gain_0 + 1e-6), (std::vector<bool>{false, true}));
  EXPECT_EQ(AppliedByEntropy<Policy>(gain_0 - 1e-6), (std::vector<bool>{true, true}));
  EXPECT_EQ(AppliedByEntropy<Policy>(5.0), (std::vector<bool>{false, false}));
  EXPECT_THROW(Policy({.min_gain_nats = std::numeric_limits<double>::quiet_NaN()}),
               std::invalid_argument);
}

TEST(SelectByEntropy, ObservationsGainingLessThanDeltaAreNotApplied) {
  ExpectThresholdBehaviour<SelectByEntropy>();
}

TEST(SelectByEntropyFast, ObservationsGainingLessThanDeltaAreNotApplied) {
  ExpectThresholdBehaviour<SelectByEntropyFast>();
}

TEST(SelectByEntropy, DenseGainIsHalfTheLogSensitivity) {
  RandomSlamState state(6, 8);
  BlockSelectionSession session(state.ekf, state.Sightings());
  for (int i = 0; i < session.size(); ++i) {
    EXPECT_NEAR(DenseInformationGain(session, i), FastInformationGain(session, i), 1e-9);
    EXPECT_NEAR(FastInformationGain(session, i), 0.5 * LogSensitivity(session, i), 1e-15);
    if (i == 2) session.Apply(i);
  }
}

// A covariance with a zero-variance block (a pose known exactly) has no log-determinant: the
// dense gain falls back to Sylvester's identity, the gain on the rest of the state.
TEST(SelectByEntropy, SingularCovarianceTakesTheGainFromSylvester) {
  BlockEkf ekf;
  const int point = ekf.RegisterKind({2, {}, false});
  const testing::PointFixModel fix;
  const Eigen::Matrix2d I = Eigen::Matrix2d::Identity();
  ekf.AddBlock(kPoseKind, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero());
  const int l = ekf.AddBlock(point, Eigen::Vector2d(1, 2), I);
  std::vector<MatchedObservation> matched = {{&fix, {l}, 1, Eigen::Vector2d(1.1, 2.0), 0.01 * I}};
  BlockSelectionSession session(ekf, matched);
  ASSERT_FALSE(std::isfinite(session.LogDetCovariance()));
  EXPECT_NEAR(DenseInformationGain(session, 0), std::log(101.0), 1e-12);
  SelectByEntropy({.min_gain_nats = 4.0}).Select(session);
  EXPECT_TRUE(session.applied(0));
}

}  // namespace
}  // namespace slamkit
