// The update pipeline seen from a pose block other than 0: two robots in one BlockEkf and point
// landmarks, started and matched by the second robot. Against the dense textbook EKF and against
// the same scans with the robots' blocks swapped.

#include "slamkit/filters/ekf_slam/update_pipeline.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <utility>
#include <vector>

#include "filters/dense_reference.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/filters/ekf_slam/point_landmarks.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace update_pipeline_test {

using testing::DenseEkf;
using testing::MaxAbsDiff;

const Pose2 kRobotA(0.0, 0.0, 0.0);
const Pose2 kRobotB(6.0, 2.0, 0.7);
// Landmark 0 is seen by robot B alone; robot A maps landmarks 1 and 2, which B then sights.
const std::vector<Eigen::Vector2d> kLandmarks = {{9.0, 5.0}, {5.0, 6.0}, {7.0, -2.0}};

Eigen::Matrix3d CovA() {
  return Eigen::Vector3d(0.02, 0.03, 0.004).asDiagonal();
}
Eigen::Matrix3d CovB() {
  Eigen::Matrix3d P;
  P << 0.09, 0.01, 0.002, 0.01, 0.05, -0.001, 0.002, -0.001, 0.006;
  return P;
}

struct Scan {
  int observer;  // 0: robot A, 1: robot B (in the usual layout, A in block 0)
  std::vector<PointObservation> sightings;
  std::vector<int> landmarks;  // what each sighting shows
  bool matched;                // sightings of mapped landmarks (else they start them)
};

PointObservation Sighting(const RangeBearingModel& sensor, const Pose2& from,
                          const Eigen::Vector2d& l, const Eigen::Vector2d& noise) {
  PointObservation obs;
  obs.z = sensor.Predict(from, l) + noise;
  obs.R = Eigen::Vector2d(0.01, 0.0004).asDiagonal();
  return obs;
}

std::vector<Scan> Scans(const RangeBearingModel& sensor) {
  const auto& l = kLandmarks;
  return {
      {1, {Sighting(sensor, kRobotB, l[0], {0.0, 0.0})}, {0}, false},
      {0,
       {Sighting(sensor, kRobotA, l[1], {0.0, 0.0}), Sighting(sensor, kRobotA, l[2], {0.0, 0.0})},
       {1, 2},
       false},
      {1,
       {Sighting(sensor, kRobotB, l[1], {0.05, -0.01}),
        Sighting(sensor, kRobotB, l[2], {-0.04, 0.015})},
       {1, 2},
       true}};
}

// Robot `first` in block 0, `second` in block 1, uncorrelated; then the landmarks' blocks.
struct TwoRobots {
  RangeBearingModel sensor;
  BlockEkf ekf{16};
  PointLandmarkModel model;
  PointLandmarkMap map;
  NearestNeighbourAssociator associator;
  SelectAll select_all;

  TwoRobots(const Pose2& first, const Eigen::Matrix3d& P_first, const Pose2& second,
            const Eigen::Matrix3d& P_second)
      : model(sensor, ekf.RegisterKind({2, {}, false}), 0.0) {
    ekf.AddBlock(kPoseKind, first.vector(), P_first);
    ekf.AddBlock(kPoseKind, second.vector(), P_second);
  }

  // One scan through the pipeline from pose block `observer`; its decisions.
  std::vector<AssociationDecision> Run(int observer, const std::vector<PointObservation>& z) {
    const std::vector<char> none;
    PointSightings points({&model, &model, &associator}, map, z, none);
    LandmarkSightings* const kinds[] = {&points};
    UpdatePipeline pipeline(ekf, observer, kinds);
    pipeline.Run(select_all, false);
    ekf.ApplyPendingDowndate();
    return pipeline.Decisions(0);
  }
};

// The textbook EKF of the same scans (x = [A, B, l_0, l_1, l_2]).
DenseEkf DenseReference(const RangeBearingModel& sensor) {
  DenseEkf dense;
  dense.x.resize(6);
  dense.x << kRobotA.vector(), kRobotB.vector();
  dense.P = Eigen::MatrixXd::Zero(6, 6);
  dense.P.topLeftCorner(3, 3) = CovA();
  dense.P.bottomRightCorner(3, 3) = CovB();
  dense.angles = {2, 5};
  for (const Scan& scan : Scans(sensor)) {
    const int pose = 3 * scan.observer;
    for (std::size_t k = 0; k < scan.sightings.size(); ++k) {
      const PointObservation& obs = scan.sightings[k];
      const Pose2 x(dense.x.segment<3>(pose));
      Eigen::Matrix<double, 2, 3> J_x;
      Eigen::Matrix2d J_l;
      if (!scan.matched) {
        const Eigen::Vector2d l = sensor.Invert(x, obs.z, &J_x, &J_l);
        dense.Augment(l, dense.Spread(J_x, pose), J_l, obs.R);
        continue;
      }
      const int offset = 6 + 2 * scan.landmarks[k];
      const Eigen::Vector2d z_pred = sensor.Predict(x, dense.x.segment<2>(offset), &J_x, &J_l);
      Eigen::MatrixXd H = dense.Spread(J_x, pose);
      H.middleCols(offset, 2) = J_l;
      dense.Update(sensor.Innovation(obs.z, z_pred), H, obs.R);
    }
  }
  return dense;
}

TEST(UpdatePipeline, SecondPoseBlockMapsAndUpdatesAsTheDenseEkf) {
  TwoRobots robots(kRobotA, CovA(), kRobotB, CovB());
  const std::vector<Scan> scans = Scans(robots.sensor);

  // Robot B starts landmark 0: placed from B's pose, not from A's, and correlated with B alone.
  const std::vector<AssociationDecision> first = robots.Run(1, scans[0].sightings);
  ASSERT_EQ(robots.map.size(), 1);
  EXPECT_EQ(first[0].kind, AssociationDecision::Kind::kNew);
  const int block = robots.map.Block(0);
  EXPECT_LT((robots.ekf.Mean(block) - kLandmarks[0]).norm(), 1e-12);
  EXPECT_GT(
      (robots.ekf.Mean(block) - robots.sensor.Invert(kRobotA, scans[0].sightings[0].z)).norm(),
      1.0);
  EXPECT_GT(robots.ekf.CovarianceBlock(1, block).norm(), 1e-3);
  EXPECT_EQ(robots.ekf.CovarianceBlock(0, block).norm(), 0.0);

  robots.Run(0, scans[1].sightings);
  ASSERT_EQ(robots.map.size(), 3);
  const Eigen::MatrixXd P_before = robots.ekf.Covariance();

  // Robot B sights the landmarks A mapped: matched, from B's pose.
  const std::vector<AssociationDecision> third = robots.Run(1, scans[2].sightings);
  ASSERT_EQ(robots.map.size(), 3);
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(third[k].kind, AssociationDecision::Kind::kMatched);
    EXPECT_EQ(third[k].landmark, k + 1);
  }
  const Eigen::MatrixXd P_after = robots.ekf.Covariance();
  // Robot B's pose and both landmarks are known better for it.
  for (const auto& [offset, dim] : {std::pair{3, 3}, std::pair{8, 2}, std::pair{10, 2}}) {
    const double after = P_after.block(offset, offset, dim, dim).determinant();
    EXPECT_LT(after, 0.99 * P_before.block(offset, offset, dim, dim).determinant());
  }

  const DenseEkf dense = DenseReference(robots.sensor);
  EXPECT_LT(MaxAbsDiff(robots.ekf.State(), dense.x), 1e-10);
  EXPECT_LT(MaxAbsDiff(P_after, dense.P), 1e-10);
}

TEST(UpdatePipeline, SwappingTheRobotsBlocksSwapsTheResult) {
  TwoRobots b_second(kRobotA, CovA(), kRobotB, CovB());
  TwoRobots b_first(kRobotB, CovB(), kRobotA, CovA());
  for (const Scan& scan : Scans(b_second.sensor)) {
    b_second.Run(scan.observer, scan.sightings);
    b_first.Run(1 - scan.observer, scan.sightings);
  }
  ASSERT_EQ(b_first.ekf.StateSize(), 12);
  ASSERT_EQ(b_second.ekf.StateSize(), 12);
  // The same state with the two pose blocks' places exchanged.
  Eigen::PermutationMatrix<Eigen::Dynamic> swap(12);
  swap.indices() << 3, 4, 5, 0, 1, 2, 6, 7, 8, 9, 10, 11;
  const Eigen::VectorXd x = swap * b_first.ekf.State();
  const Eigen::MatrixXd P = swap * b_first.ekf.Covariance() * swap.transpose();
  EXPECT_LT(MaxAbsDiff(x, b_second.ekf.State()), 1e-12);
  EXPECT_LT(MaxAbsDiff(P, b_second.ekf.Covariance()), 1e-12);
}

TEST(UpdatePipeline, StepsOneByOneAndTakenLandmarks) {
  TwoRobots robots(kRobotA, CovA(), kRobotB, CovB());
  const std::vector<Scan> scans = Scans(robots.sensor);
  robots.Run(1, scans[0].sightings);
  robots.Run(0, scans[1].sightings);
  std::vector<char> taken;
  MarkTaken(std::vector<AssociationDecision>{{AssociationDecision::Kind::kMatched, 1, 0.0}}, taken);
  PointSightings points({&robots.model, &robots.model, &robots.associator}, robots.map,
                        scans[2].sightings, taken);
  LandmarkSightings* const kinds[] = {&points};
  UpdatePipeline pipeline(robots.ekf, 1, kinds);
  pipeline.Associate();
  // Landmark 1 is taken: its sighting is near no other, so it starts a landmark.
  EXPECT_EQ(pipeline.Decisions(0)[0].kind, AssociationDecision::Kind::kNew);
  EXPECT_EQ(pipeline.Decisions(0)[1].kind, AssociationDecision::Kind::kMatched);
  const SelectionStats stats = pipeline.SelectAndUpdate(robots.select_all, false);
  EXPECT_EQ(stats.candidates, 1);
  EXPECT_EQ(stats.applied, 1);
  pipeline.Augment();
  EXPECT_EQ(pipeline.Decisions(0)[1].landmark, 2);
  EXPECT_EQ(pipeline.Decisions(0)[0].landmark, 3);
  EXPECT_EQ(robots.map.size(), 4);
}

}  // namespace update_pipeline_test
}  // namespace slamkit
