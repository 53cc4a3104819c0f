#include "slamkit/eval/innovation_check.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "slamkit/core/rng.hpp"

namespace slamkit {
namespace {

constexpr double kGate = 9.2103;  // χ²(2) at 99 %

// A log of `landmarks` landmarks sighted `reobservations` more times, whose innovations are
// those of a filter with its covariance `covariance_scale` times too small: how many of the
// sightings match no landmark (the first sightings and the re-observations outside the gate).
long OutsideGate(Rng& rng, long landmarks, long reobservations, double covariance_scale) {
  long outside = landmarks;
  for (long i = 0; i < reobservations; ++i) {
    const double x = rng.Normal(), y = rng.Normal();
    if (covariance_scale * (x * x + y * y) > kGate) ++outside;
  }
  return outside;
}

TEST(InnovationCheck, ARightNoiseModelMissesTheGateAsOftenAsItsTail) {
  Rng rng(7);
  const long landmarks = 150, reobservations = 3500;
  const long outside = OutsideGate(rng, landmarks, reobservations, 1.0);
  const InnovationCheck check =
      CheckInnovations(landmarks + reobservations, outside, landmarks, 2, kGate);
  EXPECT_NEAR(check.expected_share, 0.01, 1e-5);
  EXPECT_NEAR(check.reobservations_outside_share, 0.01, 0.005);
  EXPECT_GT(check.band_hi, 0.01);
  EXPECT_LT(check.band_hi, 0.015);
  EXPECT_EQ(check.verdict, InnovationVerdict::kConsistent);
  EXPECT_FALSE(check.warn());
}

// Innovations twice as wide as the filter believes (covariance 4 times too small) miss their
// gates a third of the time.
TEST(InnovationCheck, AnOverconfidentFilterIsFlagged) {
  Rng rng(8);
  const long landmarks = 150, reobservations = 3500;
  const long outside = OutsideGate(rng, landmarks, reobservations, 4.0);
  const InnovationCheck check =
      CheckInnovations(landmarks + reobservations, outside, landmarks, 2, kGate);
  EXPECT_NEAR(check.reobservations_outside_share, 0.316, 0.03);
  EXPECT_EQ(check.verdict, InnovationVerdict::kNoiseTooSmall);
  EXPECT_TRUE(check.warn());
  EXPECT_EQ(VerdictName(check.verdict), "noise_too_small");
}

TEST(InnovationCheck, NoVerdictWithoutIdsOrWithFewReobservations) {
  EXPECT_EQ(CheckInnovations(1000, 500, 0, 2, kGate).verdict, InnovationVerdict::kTooFew);
  EXPECT_EQ(CheckInnovations(150, 60, 100, 2, kGate).verdict, InnovationVerdict::kTooFew);
  // Fewer misses than ids (landmarks merged) is not judged: the share stays at zero.
  const InnovationCheck merged = CheckInnovations(4000, 100, 150, 2, kGate);
  EXPECT_EQ(merged.reobservations_outside_share, 0.0);
  EXPECT_EQ(merged.verdict, InnovationVerdict::kConsistent);
}

TEST(InnovationCheck, RejectsImpossibleCounts) {
  EXPECT_THROW(CheckInnovations(10, 11, 1, 2, kGate), std::invalid_argument);
  EXPECT_THROW(CheckInnovations(10, 5, 1, 0, kGate), std::invalid_argument);
  EXPECT_THROW(CheckInnovations(10, 5, 1, 2, 0.0), std::invalid_argument);
  InnovationCheckParams params;
  params.max_ratio = 1.0;
  EXPECT_THROW(CheckInnovations(10, 5, 1, 2, kGate, params), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
