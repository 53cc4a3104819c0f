// How a run on a log is scored (runners/common): the estimate and the raw odometry against the
// same relations and reference, what a partial run is scored on, and a failure kept as a note.
#include "slamkit/runners/common/log_scoring.hpp"

#include <gtest/gtest.h>

namespace slamkit {
namespace {

Trajectory Straight(int poses, double drift_y_per_pose) {
  Trajectory t;
  for (int i = 0; i < poses; ++i) t.push_back({1.0 * i, Pose2(1.0 * i, drift_y_per_pose * i, 0)});
  return t;
}

// An odometry that bends away: no rigid alignment can take it onto a straight path.
Trajectory Bent(int poses) {
  Trajectory t;
  for (int i = 0; i < poses; ++i) t.push_back({1.0 * i, Pose2(1.0 * i, 0.05 * i * i, 0)});
  return t;
}

std::vector<PoseRelation> Steps(int poses) {
  std::vector<PoseRelation> r;
  for (int i = 0; i + 1 < poses; ++i) r.push_back({1.0 * i, 1.0 + i, Pose2(1.0, 0.0, 0.0)});
  return r;
}

TEST(LogScoring, ScoresTheEstimateAndTheOdometryAgainstTheSameData) {
  const Trajectory truth = Straight(10, 0.0);
  const LogEvaluation e = EvaluateOnLog(truth, Bent(10), Steps(10), truth, LogScoringParams{});
  ASSERT_TRUE(e.relations && e.odometry_relations && e.reference && e.odometry_reference);
  EXPECT_NEAR(e.relations->trans_mean_m, 0.0, 1e-12);
  EXPECT_GT(e.odometry_relations->trans_mean_m, 0.1);
  EXPECT_NEAR(e.reference->ate.rmse_m, 0.0, 1e-12);
  EXPECT_GT(e.odometry_reference->ate.rmse_m, 0.1);
  EXPECT_TRUE(e.error.empty());
  nlohmann::json metrics;
  AddErrorMetrics(&*e.relations, &*e.reference, metrics);
  AddBaselineMetrics(e, metrics);
  EXPECT_EQ(metrics["relations"], 9);
  EXPECT_EQ(metrics["odometry_relations_trans_mean_m"], e.odometry_relations->trans_mean_m);
  EXPECT_EQ(metrics["odometry_ate_rmse_m"], e.odometry_reference->ate.rmse_m);
  EXPECT_FALSE(metrics.contains("evaluation_error"));
}

TEST(LogScoring, APartialRunIsScoredOnWhatItCovered) {
  const Trajectory truth = Straight(10, 0.0);
  const Trajectory first_half(truth.begin(), truth.begin() + 5);
  const LogEvaluation e = EvaluateOnLog(first_half, Straight(10, 0.0), Steps(10), truth,
                                        {.pair_by = PairBy::kIndex, .partial_log = true});
  ASSERT_TRUE(e.relations && e.reference);
  EXPECT_EQ(e.relations->count, 4);
  EXPECT_NEAR(e.reference->ate.rmse_m, 0.0, 1e-12);
}

TEST(LogScoring, AFailingEvaluationIsANoteNotAnException) {
  Trajectory unpaired = Straight(3, 0.0);
  for (StampedPose& p : unpaired) p.t_s += 1000.0;  // no time in common with the estimate
  const LogEvaluation e =
      EvaluateOnLog(Straight(3, 0.0), Straight(3, 0.0), {}, unpaired, LogScoringParams{});
  EXPECT_FALSE(e.error.empty());
  nlohmann::json metrics;
  AddBaselineMetrics(e, metrics);
  EXPECT_EQ(metrics["evaluation_error"], e.error);
}

}  // namespace
}  // namespace slamkit
