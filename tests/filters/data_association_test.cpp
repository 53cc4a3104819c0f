#include "slamkit/filters/data_association.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace slamkit {
namespace {

TEST(NearestNeighbour, MatchesNearestInsideGate) {
  const NearestNeighbourAssociator nn({.gate_chi2 = 9.0, .new_landmark_chi2 = 16.0});
  const std::vector<AssociationCandidate> c = {{0, 12.0}, {1, 3.0}, {2, 5.0}};
  const AssociationDecision d = nn.Associate(c);
  EXPECT_EQ(d.kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d.landmark, 1);
  EXPECT_DOUBLE_EQ(d.distance_chi2, 3.0);
}

TEST(NearestNeighbour, DropsAmbiguousBetweenGates) {
  const NearestNeighbourAssociator nn({.gate_chi2 = 9.0, .new_landmark_chi2 = 16.0});
  const std::vector<AssociationCandidate> c = {{0, 12.0}, {1, 20.0}};
  const AssociationDecision d = nn.Associate(c);
  EXPECT_EQ(d.kind, AssociationDecision::Kind::kDropped);
  EXPECT_EQ(d.landmark, -1);
}

TEST(NearestNeighbour, NewWhenFarFromAllOrNoCandidates) {
  const NearestNeighbourAssociator nn({.gate_chi2 = 9.0, .new_landmark_chi2 = 16.0});
  const std::vector<AssociationCandidate> far = {{0, 16.5}};
  EXPECT_EQ(nn.Associate(far).kind, AssociationDecision::Kind::kNew);
  EXPECT_EQ(nn.Associate({}).kind, AssociationDecision::Kind::kNew);
}

}  // namespace
}  // namespace slamkit
