#include "slamkit/eval/errors.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <vector>

namespace slamkit {
namespace {

// Landmark 0 carries the reference's id 7 six times and id 8 twice; landmark 1 carries id 8
// three times: the one-to-one matching takes 0 -> 7 and 1 -> 8, and the agreement counts the
// sightings on those pairs (9 of 12, one sighting unmapped).
TEST(AssociationAgreement, MatchesOneToOneByTheLargestSharedCounts) {
  std::vector<std::pair<int, LandmarkId>> assigned;
  for (int i = 0; i < 6; ++i) assigned.push_back({0, 7});
  for (int i = 0; i < 2; ++i) assigned.push_back({0, 8});
  for (int i = 0; i < 3; ++i) assigned.push_back({1, 8});
  assigned.push_back({-1, 9});
  const IdAgreement a = AssociationAgreement(assigned, 12);
  EXPECT_DOUBLE_EQ(a.share, 9.0 / 12.0);
  ASSERT_EQ(a.pairs.size(), 2u);
  EXPECT_EQ(a.pairs.at(0), 7);
  EXPECT_EQ(a.pairs.at(1), 8);
  EXPECT_DOUBLE_EQ(AssociationAgreement({}, 0).share, 1.0);
}

TEST(Nees, IsMahalanobisOfError) {
  Eigen::Matrix3d C = Eigen::Vector3d(4.0, 1.0, 0.25).asDiagonal();
  EXPECT_NEAR(Nees({2.0, 1.0, 0.5}, C), 1.0 + 1.0 + 1.0, 1e-12);
}

TEST(Nees, MatchesTheInverseOnACorrelatedCovariance) {
  Eigen::Matrix3d A;
  A << 1.0, 0.3, -0.2, 0.0, 0.5, 0.1, 0.0, 0.0, 0.2;
  const Eigen::Matrix3d C = A * A.transpose();
  const Eigen::Vector3d e(0.3, -0.7, 0.05);
  EXPECT_NEAR(Nees(e, C), e.dot(C.inverse() * e), 1e-9);
}

// A covariance that is singular (particles collapsed onto a line) or indefinite (rounding) has no
// NEES; LDLT used to return a finite, even negative, number for both.
TEST(Nees, IsInfiniteWithoutAPositiveDefiniteCovariance) {
  const Eigen::Matrix3d singular = Eigen::Vector3d(1.0, 1.0, 0.0).asDiagonal();
  EXPECT_TRUE(std::isinf(Nees({0.1, 0.1, 0.01}, singular)));
  Eigen::Matrix3d indefinite = Eigen::Matrix3d::Identity();
  indefinite(2, 2) = -1e-12;
  const double nees = Nees({0.1, 0.1, 0.01}, indefinite);
  EXPECT_TRUE(std::isinf(nees) && nees > 0.0);
}

// No error where the covariance claims certainty is no inconsistency: the other directions count.
TEST(Nees, IgnoresAnExactDirectionWithoutError) {
  EXPECT_EQ(Nees(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Zero()), 0.0);
  const Eigen::Matrix3d singular = Eigen::Vector3d(4.0, 1.0, 0.0).asDiagonal();
  EXPECT_NEAR(Nees({2.0, 1.0, 0.0}, singular), 2.0, 1e-12);
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
