#include "slamkit/eval/consistency.hpp"

#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"

namespace slamkit {
namespace {

TEST(AneesBand, MatchesPublishedBandForFiftyRunsThreeDof) {
  const ChiSquareBand band = AneesBand(50, 3);
  EXPECT_NEAR(band.lo, 2.360, 5e-4);
  EXPECT_NEAR(band.hi, 3.716, 5e-4);
}

TEST(ChiSquareQuantile, MatchesTableValues) {
  EXPECT_NEAR(ChiSquareQuantile(2, 0.99), 9.2103, 1e-4);
  EXPECT_NEAR(ChiSquareQuantile(1, 0.95), 3.8415, 1e-4);
  EXPECT_THROW(ChiSquareQuantile(0, 0.5), std::invalid_argument);
}

// The band must hold the ANEES of a consistent estimator 95 % of the time.
TEST(AneesBand, CoversSimulatedConsistentEstimator) {
  Rng rng(21);
  const int runs = 50, trials = 2000;
  const ChiSquareBand band = AneesBand(runs, 3);
  int inside = 0;
  for (int t = 0; t < trials; ++t) {
    double sum = 0.0;
    for (int r = 0; r < runs * 3; ++r) {
      const double v = rng.Normal();
      sum += v * v;
    }
    inside += band.Contains(sum / runs) ? 1 : 0;
  }
  EXPECT_NEAR(double(inside) / trials, 0.95, 0.015);
}

}  // namespace
}  // namespace slamkit
