#include "slamkit/eval/trajectory_errors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace slamkit {
namespace {

const Trajectory kEstimate = {{0.0, Pose2(0, 0, 0)}, {1.0, Pose2(1, 0, 0)},
                              {2.0, Pose2(1, 1, M_PI / 2)}};

// Hand-computed: the three relations have translational errors 0, 0.2, 0 m and rotational
// errors 0, 0, 0.1 rad.
TEST(Relations, MatchHandComputedErrors) {
  const std::vector<PoseRelation> relations = {{0.0, 1.0, Pose2(1, 0, 0)},
                                               {1.0, 2.0, Pose2(0, 1.2, M_PI / 2)},
                                               {0.0, 2.0, Pose2(1, 1, M_PI / 2 - 0.1)}};
  const RelationErrorStats s = EvaluateRelations(kEstimate, relations);
  EXPECT_EQ(s.count, 3);
  EXPECT_NEAR(s.trans_mean_m, 0.2 / 3.0, 1e-12);
  EXPECT_NEAR(s.trans_std_m, std::sqrt((2 * std::pow(0.2 / 3, 2) + std::pow(0.4 / 3, 2)) / 3),
              1e-12);
  const double rot_deg = 0.1 * 180.0 / M_PI;
  EXPECT_NEAR(s.rot_mean_deg, rot_deg / 3.0, 1e-9);
  EXPECT_NEAR(s.rot_std_deg, rot_deg * std::sqrt(2.0) / 3.0, 1e-9);
}

TEST(Relations, PerfectEstimateHasZeroErrorWhateverTheFrame) {
  // Relations are frame-free: moving the whole estimate rigidly changes nothing.
  const Pose2 shift(5.0, -3.0, 1.0);
  Trajectory moved;
  for (const StampedPose& p : kEstimate) moved.push_back({p.t_s, shift.Compose(p.pose)});
  std::vector<PoseRelation> relations;
  for (int i = 0; i + 1 < 3; ++i) {
    relations.push_back({kEstimate[i].t_s, kEstimate[i + 1].t_s,
                         kEstimate[i].pose.Between(kEstimate[i + 1].pose)});
  }
  const RelationErrorStats s = EvaluateRelations(moved, relations);
  EXPECT_NEAR(s.trans_mean_m, 0.0, 1e-12);
  EXPECT_NEAR(s.rot_mean_deg, 0.0, 1e-9);
}

TEST(Relations, CoveredKeepsOnlyRelationsWithBothPoses) {
  const std::vector<PoseRelation> relations = {{0.0, 1.0, Pose2()}, {1.0, 7.0, Pose2()},
                                               {2.0, 0.0, Pose2()}};
  const auto covered = RelationsCovered(kEstimate, relations);
  ASSERT_EQ(covered.size(), 2u);
  EXPECT_EQ(covered[1].t1_s, 2.0);
}

// Issue 9: a relation stamp between two scans is interpolated (it used to end the run with an
// error after the filter had run); one outside the trajectory is skipped and counted.
TEST(Relations, StampsBetweenPosesAreInterpolatedAndOutsideOnesSkipped) {
  // At t = 1.5, halfway from (1, 0, 0) to (1, 1, π/2): (1, 0.5, π/4), by hand.
  const std::vector<PoseRelation> relations = {{0.0, 1.5, Pose2(1, 0.5, M_PI / 4)},
                                               {0.0, 2.5, Pose2()},
                                               {-1.0, 1.0, Pose2()}};
  const RelationErrorStats s = EvaluateRelations(kEstimate, relations);
  EXPECT_EQ(s.count, 1);
  EXPECT_EQ(s.skipped, 2);
  EXPECT_NEAR(s.trans_mean_m, 0.0, 1e-12);
  EXPECT_NEAR(s.rot_mean_deg, 0.0, 1e-9);
}

// Relations none of which the trajectory covers (another log's) are an error, not a perfect 0 m.
TEST(Relations, NoneWithinTheTrajectoryIsAnError) {
  const std::vector<PoseRelation> relations = {{100.0, 101.0, Pose2()}, {102.0, 103.0, Pose2()}};
  try {
    EvaluateRelations(kEstimate, relations);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("none of the 2 relations lies within the trajectory's "
                                         "time span (0.000 to 2.000 s; the relations start from "
                                         "100.000 to 102.000 s)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_EQ(EvaluateRelations(kEstimate, {}).count, 0);  // no relations at all: nothing to say
}

TEST(InterpolatePoseAt, MatchesHandComputedPosesAndTakesTheShorterArc) {
  const Pose2 q = *InterpolatePoseAt(kEstimate, 1.25, 1e-3);
  EXPECT_NEAR(q.x(), 1.0, 1e-12);
  EXPECT_NEAR(q.y(), 0.25, 1e-12);
  EXPECT_NEAR(q.theta(), M_PI / 8, 1e-12);
  EXPECT_EQ(InterpolatePoseAt(kEstimate, 1.0004, 1e-3)->vector(), kEstimate[1].pose.vector());
  EXPECT_FALSE(InterpolatePoseAt(kEstimate, 2.1, 1e-3));
  EXPECT_FALSE(InterpolatePoseAt(kEstimate, -0.1, 1e-3));
  // From 170° to -170°: through 180°, not through 0°.
  const Trajectory wrap = {{0.0, Pose2(0, 0, 170 * M_PI / 180)}, {1.0, Pose2(0, 0, -170 * M_PI / 180)}};
  EXPECT_NEAR(std::abs(InterpolatePoseAt(wrap, 0.5, 1e-3)->theta()), M_PI, 1e-12);
}

TEST(FindPoseAt, NearestWithinTolerance) {
  EXPECT_EQ(FindPoseAt(kEstimate, 1.0004, 1e-3), 1);
  EXPECT_EQ(FindPoseAt(kEstimate, 0.9996, 1e-3), 1);
  EXPECT_EQ(FindPoseAt(kEstimate, 1.5, 1e-3), -1);
  EXPECT_EQ(FindPoseAt(kEstimate, 2.0, 1e-3), 2);
  EXPECT_EQ(FindPoseAt(kEstimate, -0.0005, 1e-3), 0);
}

TEST(AbsoluteTrajectoryError, IgnoresRigidMotionAndMeasuresTheRest) {
  Trajectory reference, estimate;
  const Pose2 frame(2.0, 1.0, 0.5);
  for (int i = 0; i < 10; ++i) {
    const Pose2 p(i * 1.0, (i % 3) * 0.5, 0.1 * i);
    reference.push_back({double(i), p});
    estimate.push_back({double(i), frame.Compose(p)});
  }
  EXPECT_NEAR(AbsoluteTrajectoryError(estimate, reference).rmse_m, 0.0, 1e-9);
  // A square grown by 10 % cannot be aligned onto the original by a rigid motion: every corner
  // stays 0.1·√2 m away.
  Trajectory square, grown;
  const std::vector<Eigen::Vector2d> corners = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};
  for (int i = 0; i < 4; ++i) {
    square.push_back({double(i), Pose2(corners[i].x(), corners[i].y(), 0)});
    grown.push_back({double(i), Pose2(1.1 * corners[i].x(), 1.1 * corners[i].y(), 0)});
  }
  const auto ate = AbsoluteTrajectoryError(grown, square);
  EXPECT_EQ(ate.count, 4);
  EXPECT_NEAR(ate.rmse_m, 0.1 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(ate.max_m, 0.1 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(ate.mean_m, 0.1 * std::sqrt(2.0), 1e-12);
}

TEST(CompareWithReference, PairsByIndexWhateverTheTimestamps) {
  Trajectory reference, estimate;
  for (int i = 0; i < 5; ++i) {
    reference.push_back({7.0, Pose2(i, 0, 0)});  // all stamped alike, as in csail-corrected
    estimate.push_back({7.0, Pose2(i == 4 ? 4.3 : i, 0, 0)});
  }
  const ReferenceComparison c = CompareWithReference(estimate, reference);
  EXPECT_EQ(c.rpe.count, 4);
  EXPECT_NEAR(c.rpe.trans_mean_m, 0.3 / 4.0, 1e-12);  // only the last step is 0.3 m long
  EXPECT_EQ(c.ate.count, 5);
  EXPECT_GT(c.ate.rmse_m, 0.0);
  EXPECT_THROW(CompareWithReference(estimate, Trajectory(3)), std::invalid_argument);
}

TEST(CompareWithReference, PairsByTimeLeavingUnpairedPosesOut) {
  Trajectory reference, estimate;
  for (int i = 0; i < 6; ++i) reference.push_back({double(i), Pose2(i, 0, 0)});
  // The estimate misses t = 2 and has an extra pose at 2.5 that nothing pairs with.
  for (double t : {0.0, 1.0, 2.5, 3.0, 4.0, 5.0}) estimate.push_back({t, Pose2(t, 0, 0)});
  const ReferenceComparison c = CompareWithReference(estimate, reference, PairBy::kTime);
  EXPECT_EQ(c.ate.count, 5);
  EXPECT_NEAR(c.ate.rmse_m, 0.0, 1e-9);
  const Trajectory far = {{100.0, Pose2()}};
  EXPECT_THROW(CompareWithReference(far, reference, PairBy::kTime), std::invalid_argument);
  EXPECT_THROW(CompareWithReference(far, reference, PairBy::kIndex), std::invalid_argument);
}

TEST(TimestampProblem, RepeatedAndBackwardStampsAreNamed) {
  EXPECT_EQ(TimestampProblem(kEstimate), "");
  const Trajectory repeated = {{0.0, Pose2()}, {0.0, Pose2()}, {0.0, Pose2()}};
  EXPECT_NE(TimestampProblem(repeated).find("2 of 3 timestamps repeat"), std::string::npos);
  const Trajectory backwards = {{0.0, Pose2()}, {1.0, Pose2()}, {0.5, Pose2()}};
  EXPECT_NE(TimestampProblem(backwards).find("1 go backwards"), std::string::npos);
}

// Issue 9: evo rejects a TUM file whose times do not increase (Intel's jitter, CSAIL's repeats).
TEST(WithIncreasingTimes, PushesRepeatsAndStepsBackForwardAndKeepsTheRest) {
  const Trajectory t = {{10.0, Pose2(1, 0, 0)}, {10.0, Pose2()}, {9.5, Pose2()},
                        {11.0, Pose2()}, {11.0, Pose2()}};
  int moved = 0;
  const Trajectory out = WithIncreasingTimes(t, 1e-3, &moved);
  EXPECT_EQ(moved, 3);
  const std::vector<double> expected = {10.0, 10.001, 10.002, 11.0, 11.001};
  ASSERT_EQ(out.size(), expected.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_NEAR(out[i].t_s, expected[i], 1e-12) << i;
    if (i > 0) {
      EXPECT_GT(out[i].t_s, out[i - 1].t_s) << i;
    }
  }
  EXPECT_EQ(out[0].pose.vector(), t[0].pose.vector());
  EXPECT_EQ(TimestampProblem(out, 1e-4), "");
}

}  // namespace
}  // namespace slamkit
