#include "slamkit/eval/errors.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace slamkit {
namespace {

TEST(Nees, IsMahalanobisOfError) {
  Eigen::Matrix3d C = Eigen::Vector3d(4.0, 1.0, 0.25).asDiagonal();
  EXPECT_NEAR(Nees({2.0, 1.0, 0.5}, C), 1.0 + 1.0 + 1.0, 1e-12);
}

TEST(PoseRmse, SeparatesPositionAndHeading) {
  const std::vector<Eigen::Vector3d> e = {{3.0, 4.0, 0.1}, {0.0, 0.0, -0.3}};
  const PoseRmse r = ComputePoseRmse(e);
  EXPECT_NEAR(r.position_m, std::sqrt(25.0 / 2.0), 1e-12);
  EXPECT_NEAR(r.heading_rad, std::sqrt((0.01 + 0.09) / 2.0), 1e-12);
}

TEST(AssociationScorer, CountsPrecisionAndRecall) {
  using Kind = AssociationOutcome;
  AssociationScorer s;
  s.Add(7, Kind::kNew, kNoLandmark);      // creates 7
  s.Add(8, Kind::kNew, kNoLandmark);      // creates 8
  s.Add(7, Kind::kMatched, 7);            // correct
  s.Add(8, Kind::kMatched, 7);            // wrong landmark
  s.Add(7, Kind::kDropped, kNoLandmark);  // matchable, missed
  s.Add(9, Kind::kMatched, 8);            // 9 not in map: a false match
  const AssociationScore& a = s.score();
  EXPECT_EQ(a.sightings, 6);
  EXPECT_EQ(a.matched, 3);
  EXPECT_EQ(a.correct, 1);
  EXPECT_EQ(a.matchable, 3);
  EXPECT_EQ(a.dropped, 1);
  EXPECT_NEAR(a.Precision(), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(a.Recall(), 1.0 / 3.0, 1e-12);
}

}  // namespace
}  // namespace slamkit
