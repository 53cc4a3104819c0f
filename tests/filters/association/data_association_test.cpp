#include "slamkit/filters/association/data_association.hpp"

#include <gtest/gtest.h>

#include <vector>

#include <Eigen/Core>

#include "common/translation_scan.hpp"

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

// Sightings at `z`, each with covariance variance · I.
std::vector<PointObservation> Sightings(const std::vector<Eigen::Vector2d>& z, double variance) {
  std::vector<PointObservation> sightings;
  for (const Eigen::Vector2d& zi : z) {
    PointObservation o;
    o.z = zi;
    o.R = Eigen::Matrix2d::Identity() * variance;
    sightings.push_back(o);
  }
  return sightings;
}

// A landmark mapped once from afar (σ = 2 m) and a well-mapped one (σ = 0.1 m), both within the
// gate of a sighting 0.7 m from the first and 0.3 m from the second: the first is nearer in
// Mahalanobis distance (0.12 against 4.5), the second far more likely (ln|S| 2.8 against -7.8).
testing::TranslationScan UncertainBesideCertain(const std::vector<Eigen::Vector2d>& z) {
  return testing::TranslationScan({{0.0, 0.0}, {1.0, 0.0}}, Sightings(z, 0.01),
                                  Eigen::Vector2d::Zero(),
                                  Eigen::Matrix2d::Zero(),
                                  {Eigen::Matrix2d::Identity() * 4.0,
                                   Eigen::Matrix2d::Identity() * 0.01});
}

TEST(MaximumLikelihood, TakesTheLikelierLandmarkWhereNearestNeighbourTakesTheUncertainOne) {
  const testing::TranslationScan scan = UncertainBesideCertain({{0.7, 0.0}});
  NearestNeighbourAssociator nn;
  MaximumLikelihoodAssociator ml;
  const std::vector<AssociationDecision> by_distance = nn.Associate(scan);
  const std::vector<AssociationDecision> by_likelihood = ml.Associate(scan);
  EXPECT_EQ(by_distance[0].landmark, 0);
  ASSERT_EQ(by_likelihood[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(by_likelihood[0].landmark, 1);
  EXPECT_NEAR(by_likelihood[0].distance_chi2, 0.09 / 0.02, 1e-12);
}

// The gates are nearest neighbour's: a likelier landmark outside gate_chi2 is never taken, and a
// sighting far from every landmark is new, one between the gates dropped.
TEST(MaximumLikelihood, KeepsNearestNeighboursGates) {
  const testing::TranslationScan scan =
      UncertainBesideCertain({{0.0, 6.5}, {0.0, 9.0}, {1.0, 0.5}});
  MaximumLikelihoodAssociator ml;
  const std::vector<AssociationDecision> d = ml.Associate(scan);
  EXPECT_EQ(d[0].kind, AssociationDecision::Kind::kDropped);  // d² = 10.5 from landmark 0
  EXPECT_EQ(d[1].kind, AssociationDecision::Kind::kNew);
  EXPECT_EQ(d[2].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d[2].landmark, 0);  // landmark 1 is at d² = 12.5, outside the gate
}

// A landmark takes one sighting per scan: the second sighting near the well-mapped landmark
// falls to the other.
TEST(MaximumLikelihood, TakesEachLandmarkOncePerScan) {
  const testing::TranslationScan scan = UncertainBesideCertain({{0.9, 0.0}, {1.1, 0.0}});
  MaximumLikelihoodAssociator ml;
  const std::vector<AssociationDecision> d = ml.Associate(scan);
  EXPECT_EQ(d[0].landmark, 1);
  EXPECT_EQ(d[1].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d[1].landmark, 0);
}

// Two landmarks 1 m apart known exactly, sightings with σ = 0.2 m, the pose known.
testing::TranslationScan PairOneMetreApart(const std::vector<Eigen::Vector2d>& z) {
  return testing::TranslationScan({{0.0, 0.0}, {1.0, 0.0}}, Sightings(z, 0.04),
                                  Eigen::Vector2d::Zero(), Eigen::Matrix2d::Zero());
}

// The first sighting lies between the landmarks (d² 5.06 from landmark 0, 7.56 from 1), the
// second on landmark 0 (d² 0.06). In scan order nearest neighbour gives landmark 0 to the first,
// and the second, 22.6 from landmark 1, starts a duplicate of landmark 0; the scan's nearest
// pairs first give each sighting its own landmark.
TEST(GlobalNearestNeighbour, TheNearestPairGoesFirstWhateverTheScanOrder) {
  const testing::TranslationScan scan = PairOneMetreApart({{0.45, 0.0}, {0.05, 0.0}});
  NearestNeighbourAssociator nn;
  const std::vector<AssociationDecision> in_order = nn.Associate(scan);
  EXPECT_EQ(in_order[0].landmark, 0);
  EXPECT_EQ(in_order[1].kind, AssociationDecision::Kind::kNew);
  GlobalNearestNeighbourAssociator gnn;
  const std::vector<AssociationDecision> d = gnn.Associate(scan);
  ASSERT_EQ(d[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d[0].landmark, 1);
  EXPECT_NEAR(d[0].distance_chi2, 0.55 * 0.55 / 0.04, 1e-12);
  ASSERT_EQ(d[1].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d[1].landmark, 0);
}

// A sighting whose only landmark in the gate went to a nearer sighting of the scan is dropped (it
// may be that landmark); a sighting beyond new_landmark_chi2 from every landmark is new, one
// between the gates dropped.
TEST(GlobalNearestNeighbour, ASightingATakenLandmarkCouldExplainIsNotMappedTwice) {
  const testing::TranslationScan scan = PairOneMetreApart(
      {{-0.4, 0.0}, {-0.05, 0.0}, {-0.7, 0.0}, {-0.9, 0.0}, {1.05, 0.0}});
  NearestNeighbourAssociator nn;
  EXPECT_EQ(nn.Associate(scan)[0].kind, AssociationDecision::Kind::kMatched);
  GlobalNearestNeighbourAssociator gnn;
  const std::vector<AssociationDecision> d = gnn.Associate(scan);
  EXPECT_EQ(d[1].landmark, 0);
  EXPECT_EQ(d[4].landmark, 1);
  EXPECT_EQ(d[0].kind, AssociationDecision::Kind::kDropped);  // d² 4 from the taken landmark 0
  EXPECT_NEAR(d[0].distance_chi2, 4.0, 1e-12);
  EXPECT_EQ(d[2].kind, AssociationDecision::Kind::kDropped);  // d² 12.25: between the gates
  EXPECT_EQ(d[3].kind, AssociationDecision::Kind::kNew);      // d² 20.25
  EXPECT_EQ(d[3].landmark, -1);
}

}  // namespace
}  // namespace slamkit
