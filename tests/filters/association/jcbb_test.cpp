#include "slamkit/filters/association/jcbb.hpp"

#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "common/translation_scan.hpp"

namespace slamkit {
namespace {

using testing::TranslationScan;

// Landmarks 1 m apart in a row, the pose estimate 0.6 m behind the truth with 0.5 m of standard
// deviation: each sighting of landmarks 1-3 is nearer, one by one, to its left neighbour than to
// itself, but only the true pairing explains the whole scan with one pose error. (Seen from the
// right, nearest neighbour takes each left neighbour before its own sighting comes.)
TranslationScan ShiftedRow(std::vector<int> seen) {
  std::vector<Eigen::Vector2d> landmarks = {{0, 0}, {1, 0}, {2, 0}, {3, 0}, {0, 3}};
  const Eigen::Vector2d truth(0.6, -1.0), x_hat(0.0, -1.0);
  std::vector<PointObservation> z;
  for (int l : seen) {
    PointObservation o;
    o.z = landmarks[l] - truth;
    o.R = Eigen::Matrix2d::Identity() * 0.02 * 0.02;
    z.push_back(o);
  }
  return TranslationScan(landmarks, z, x_hat, Eigen::Matrix2d::Identity() * 0.25);
}

TEST(Jcbb, PairsTheWholeScanWhereNearestNeighbourIsMisledByThePoseError) {
  const std::vector<int> seen = {3, 2, 1, 0};
  TranslationScan scan = ShiftedRow(seen);
  NearestNeighbourAssociator nn;
  const std::vector<AssociationDecision> by_nn = nn.Associate(scan);
  int nn_right = 0;
  for (std::size_t i = 0; i < seen.size(); ++i) {
    nn_right +=
        by_nn[i].kind == AssociationDecision::Kind::kMatched && by_nn[i].landmark == seen[i];
  }
  ASSERT_LT(nn_right, 4) << "the scene must mislead nearest neighbour";
  JcbbAssociator jcbb;
  const std::vector<AssociationDecision> d = jcbb.Associate(scan);
  for (std::size_t i = 0; i < seen.size(); ++i) {
    EXPECT_EQ(d[i].kind, AssociationDecision::Kind::kMatched) << i;
    EXPECT_EQ(d[i].landmark, seen[i]) << i;
  }
  EXPECT_FALSE(jcbb.last_search_truncated());
  EXPECT_GT(jcbb.last_joint_tests(), 0);
}

TEST(Jcbb, OneObservationIsNearestNeighbour) {
  for (int l : {0, 2, 4}) {
    TranslationScan scan = ShiftedRow({l});
    const AssociationDecision nn = NearestNeighbourAssociator().Associate(scan)[0];
    const AssociationDecision j = JcbbAssociator().Associate(scan)[0];
    EXPECT_EQ(j.kind, nn.kind) << l;
    EXPECT_EQ(j.landmark, nn.landmark) << l;
  }
}

// A sighting far from every landmark is new; one only the joint test rejects is dropped.
TEST(Jcbb, UnpairedObservationsAreNewOrDroppedByTheirIndividualDistance) {
  std::vector<Eigen::Vector2d> landmarks = {{0, 0}, {1, 0}};
  std::vector<PointObservation> z(2);
  z[0].z = Eigen::Vector2d(0.0, 1.0);    // landmark 0, from the estimate itself
  z[1].z = Eigen::Vector2d(30.0, 30.0);  // nothing there
  for (auto& o : z) o.R = Eigen::Matrix2d::Identity() * 1e-4;
  TranslationScan scan(landmarks, z, Eigen::Vector2d(0, -1), Eigen::Matrix2d::Identity() * 0.01);
  const std::vector<AssociationDecision> d = JcbbAssociator().Associate(scan);
  EXPECT_EQ(d[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d[0].landmark, 0);
  EXPECT_EQ(d[1].kind, AssociationDecision::Kind::kNew);
}

// The budget cuts the search short and the best hypothesis found so far is taken: still never
// one landmark for two sightings, and every pairing jointly compatible.
TEST(Jcbb, ARunOutBudgetFallsBackToTheBestFoundSoFar) {
  const std::vector<int> seen = {3, 2, 1, 0};
  for (long budget : {0L, 1L, 2L, 3L}) {
    TranslationScan scan = ShiftedRow(seen);
    JcbbParams p;
    p.max_joint_tests = budget;
    JcbbAssociator jcbb({}, p);
    const std::vector<AssociationDecision> d = jcbb.Associate(scan);
    EXPECT_LE(jcbb.last_joint_tests(), budget);
    EXPECT_TRUE(jcbb.last_search_truncated()) << budget;
    std::set<int> used;
    int matched = 0;
    for (const AssociationDecision& a : d) {
      if (a.kind != AssociationDecision::Kind::kMatched) continue;
      ++matched;
      EXPECT_TRUE(used.insert(a.landmark).second) << "landmark " << a.landmark << " used twice";
    }
    EXPECT_LE(matched, budget);
  }
}

TEST(Jcbb, RejectsAProbabilityOutsideZeroOne) {
  JcbbParams p;
  p.joint_probability = 1.0;
  EXPECT_THROW(JcbbAssociator({}, p), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
