#include "slamkit/filters/particles/resampling.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace slamkit {
namespace {

TEST(Resampling, EffectiveSampleSizeOfUniformAndDegenerateWeights) {
  EXPECT_DOUBLE_EQ(EffectiveSampleSize(std::vector<double>(20, 1.0 / 20)), 20.0);
  std::vector<double> degenerate(20, 0.0);
  degenerate[7] = 1.0;
  EXPECT_DOUBLE_EQ(EffectiveSampleSize(degenerate), 1.0);
  std::vector<double> two(4, 0.0);
  two[0] = two[2] = 0.5;
  EXPECT_NEAR(EffectiveSampleSize(two), 2.0, 1e-12);
}

TEST(Resampling, NormaliseLogWeightsAppliesTheGain) {
  // log-weights 0 and -ln 4: weights 4:1 at gain 1, 2:1 at gain 1/2; huge magnitudes are fine.
  const std::vector<double> log_w = {-1e3, -1e3 - std::log(4.0)};
  const std::vector<double> w1 = NormaliseLogWeights(log_w);
  EXPECT_NEAR(w1[0], 0.8, 1e-12);
  const std::vector<double> w2 = NormaliseLogWeights(log_w, 0.5);
  EXPECT_NEAR(w2[0], 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(w2[0] + w2[1], 1.0, 1e-12);
}

class SchemeTest : public ::testing::TestWithParam<ResamplingScheme> {};

// Over many draws each particle is kept N · w_i times on average, and every draw gives N indices
// in increasing order.
TEST_P(SchemeTest, KeepsEachParticleInProportionToItsWeight) {
  const std::vector<double> w = {0.05, 0.0, 0.3, 0.15, 0.02, 0.08, 0.4};
  const int n = static_cast<int>(w.size());
  const int draws = 20000;
  std::vector<double> counts(n, 0.0);
  Rng rng(3);
  for (int d = 0; d < draws; ++d) {
    const std::vector<int> keep = Resample(GetParam(), w, rng);
    ASSERT_EQ(static_cast<int>(keep.size()), n);
    ASSERT_TRUE(std::is_sorted(keep.begin(), keep.end()));
    for (int k : keep) counts[k] += 1.0;
  }
  for (int i = 0; i < n; ++i) {
    EXPECT_NEAR(counts[i] / draws, n * w[i], 0.02 + 0.02 * n * w[i]) << i;
  }
  EXPECT_EQ(counts[1], 0.0);  // a zero weight is never drawn
}

INSTANTIATE_TEST_SUITE_P(AllSchemes, SchemeTest,
                         ::testing::Values(ResamplingScheme::kSystematic,
                                           ResamplingScheme::kStratified,
                                           ResamplingScheme::kMultinomial));

// The low-variance sampler keeps particle i ⌊N w_i⌋ or ⌈N w_i⌉ times, from one uniform draw.
TEST(Resampling, SystematicIsLowVarianceFromOneDraw) {
  const std::vector<double> w = {0.05, 0.3, 0.15, 0.02, 0.08, 0.4};
  const int n = static_cast<int>(w.size());
  Rng rng(11);
  for (int d = 0; d < 1000; ++d) {
    Rng once = rng;
    const std::vector<int> keep = SystematicResample(w, rng);
    once.Uniform();
    EXPECT_EQ(once.NextU64(), Rng(rng).NextU64());  // exactly one draw was taken
    for (int i = 0; i < n; ++i) {
      const double c = double(std::count(keep.begin(), keep.end(), i));
      EXPECT_GE(c, std::floor(n * w[i]) - 1e-9);
      EXPECT_LE(c, std::ceil(n * w[i]) + 1e-9);
    }
  }
}

TEST(Resampling, SystematicKeepsHeavyParticlesAndNeffMeasuresSpread) {
  Rng rng(3);
  const std::vector<double> one_heavy = {0.0, 1.0, 0.0, 0.0};
  EXPECT_EQ(SystematicResample(one_heavy, rng), (std::vector<int>{1, 1, 1, 1}));
  EXPECT_NEAR(EffectiveSampleSize(one_heavy), 1.0, 1e-12);
  const std::vector<double> uniform = {0.25, 0.25, 0.25, 0.25};
  EXPECT_EQ(SystematicResample(uniform, rng), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_NEAR(EffectiveSampleSize(uniform), 4.0, 1e-12);
  const std::vector<double> w = NormaliseLogWeights(std::vector<double>{-1000.0, -1000.0 + std::log(3.0)});
  EXPECT_NEAR(w[0], 0.25, 1e-12);
  EXPECT_NEAR(w[1], 0.75, 1e-12);
}

TEST(Resampling, SameSeedSameDraws) {
  const std::vector<double> w = {0.1, 0.2, 0.3, 0.4};
  for (ResamplingScheme s : {ResamplingScheme::kSystematic, ResamplingScheme::kStratified,
                             ResamplingScheme::kMultinomial}) {
    Rng a(5), b(5);
    EXPECT_EQ(Resample(s, w, a), Resample(s, w, b));
  }
}

}  // namespace
}  // namespace slamkit
