#include "slamkit/eval/monte_carlo.hpp"

#include <gtest/gtest.h>

#include "slamkit/io/scenario_config.hpp"

namespace slamkit {
namespace {

ScenarioParams ShortScenario(bool known_association) {
  ScenarioParams s = LoadScenario(std::string(SLAMKIT_SOURCE_DIR) + "/configs/short.yaml");
  s.ekf.association_method = known_association ? AssociationMethod::kKnown
                                                : AssociationMethod::kNearestNeighbour;
  return s;
}

// SPEC S2's consistency check: with known association the pose ANEES over 50 runs must fall in
// the two-sided 95 % χ² band [2.360, 3.716].
TEST(MonteCarlo, KnownAssociationIsConsistent) {
  MonteCarloParams params;
  params.runs = 50;
  params.seed = 2026;
  const MonteCarloResult mc = RunMonteCarlo(ShortScenario(true), params);
  EXPECT_NEAR(mc.band.lo, 2.360, 1e-3);
  EXPECT_TRUE(mc.band.Contains(mc.anees_mean))
      << "ANEES " << mc.anees_mean << " outside [" << mc.band.lo << ", " << mc.band.hi << "]";
  EXPECT_GT(mc.anees_fraction_in_band, 0.8);
  EXPECT_GT(mc.landmarks_mapped_mean, 10.0);
}

TEST(MonteCarlo, NearestNeighbourAssociationIsPreciseInSparseWorld) {
  MonteCarloParams params;
  params.runs = 20;
  params.seed = 7;
  const MonteCarloResult mc = RunMonteCarlo(ShortScenario(false), params);
  EXPECT_GT(mc.association.matched, 1000);
  EXPECT_GE(mc.association.Precision(), 0.99);
  EXPECT_GE(mc.association.Recall(), 0.99);
}

TEST(MonteCarlo, SameSeedSameResultWhateverTheThreadCount) {
  MonteCarloParams params;
  params.runs = 6;
  params.seed = 99;
  params.threads = 1;
  const MonteCarloResult one = RunMonteCarlo(ShortScenario(false), params);
  params.threads = 2;
  const MonteCarloResult two = RunMonteCarlo(ShortScenario(false), params);
  params.seed = 100;
  const MonteCarloResult other = RunMonteCarlo(ShortScenario(false), params);
  ASSERT_EQ(one.runs.size(), two.runs.size());
  for (std::size_t k = 0; k < one.runs.size(); ++k) {
    ASSERT_EQ(one.runs[k].estimate.size(), two.runs[k].estimate.size());
    for (std::size_t i = 0; i < one.runs[k].estimate.size(); ++i) {
      ASSERT_EQ(one.runs[k].estimate[i].pose.vector(), two.runs[k].estimate[i].pose.vector());
    }
    EXPECT_EQ(one.runs[k].nees, two.runs[k].nees);
  }
  EXPECT_EQ(one.anees, two.anees);
  EXPECT_NE(one.anees, other.anees);
}

}  // namespace
}  // namespace slamkit
