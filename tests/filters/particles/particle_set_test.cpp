#include "slamkit/filters/particles/particle_set.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace slamkit {
namespace {

TEST(ParticleSet, StartsUniform) {
  const ParticleSet<int> set(8, 42);
  ASSERT_EQ(set.size(), 8);
  EXPECT_EQ(set[5], 42);
  EXPECT_DOUBLE_EQ(set.EffectiveSampleSize(), 8.0);
  EXPECT_EQ(ParticleSet<int>(0, 1).size(), 1);  // at least one particle
}

TEST(ParticleSet, DegenerateWeightsGiveOneEffectiveParticle) {
  ParticleSet<int> set(8, 0);
  set.AddLogWeight(3, 1000.0);
  EXPECT_NEAR(set.EffectiveSampleSize(), 1.0, 1e-9);
  // A gain flattens the weights: log-weights 0 and ln 9 at gain 1/2 weigh 1 : 3.
  ParticleSet<int> two(2, 0);
  two.AddLogWeight(1, std::log(9.0));
  const std::vector<double> w = two.Weights(0.5);
  EXPECT_NEAR(w[1], 0.75, 1e-12);
  EXPECT_NEAR(two.EffectiveSampleSize(0.5), 1.0 / (0.75 * 0.75 + 0.25 * 0.25), 1e-12);
}

TEST(ParticleSet, ResamplesOnlyBelowTheThreshold) {
  ParticleSet<int> set(4, 0);
  for (int i = 0; i < 4; ++i) set[i] = 10 * i;
  Rng rng(1);
  set.AddLogWeight(1, 0.1);  // nearly uniform: N_eff ≈ 4 ≥ 0.5 · 4
  EXPECT_FALSE(set.ResampleIfNeeded(1.0, {}, rng));
  EXPECT_NEAR(set.last_neff(), 4.0, 0.01);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(set.source(i), i);

  set.AddLogWeight(2, 100.0);  // degenerate: every copy is of particle 2
  EXPECT_TRUE(set.ResampleIfNeeded(1.0, {}, rng));
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(set[i], 20);
    EXPECT_EQ(set.source(i), 2);
    EXPECT_EQ(set.log_weights()[i], 0.0);              // reset
    EXPECT_DOUBLE_EQ(set.total_log_weight(i), 100.0);  // kept with the copy
  }
}

TEST(ParticleSet, BestHasTheLargestTotalLogWeight) {
  ParticleSet<int> set(5, 0);
  set.AddLogWeight(1, -3.0);
  set.AddLogWeight(3, 2.0);
  set.AddLogWeight(4, 2.0);
  EXPECT_EQ(set.Best(), 3);  // the first of equals
}

}  // namespace
}  // namespace slamkit
