// Issue 32: selection policies (SPEC S1 items 2-3) plug into compressed updates unchanged: on the
// per-scan schedule, the covariance policy and the seed's dense entropy policy (which reads the
// whole covariance) make the same decisions with compressed updates as with dense ones, and the
// filters end equal.
#include <gtest/gtest.h>

#include <numbers>
#include <vector>

#include "filters/compressed_circle.hpp"
#include "slamkit/filters/selection/selection_policies.hpp"

namespace slamkit {
namespace {

using testing::RelativeDiff;

std::unique_ptr<SelectionPolicy> MakePolicy(bool entropy) {
  // With 5 cm / 0.3° sightings nearly every one gains more than the default 0.1 nats.
  if (entropy) return std::make_unique<SelectByEntropy>(EntropySelectionParams{.min_gain_nats = 1.0});
  return std::make_unique<SelectByCovariance>();
}

void ExpectSameRun(bool entropy, int steps) {
  const RangeBearingParams sensor{.max_range_m = 8.0, .fov_rad = std::numbers::pi,
                                  .sigma_range_m = 0.05, .sigma_bearing_rad = 0.005};
  testing::CircleDrive drive(15.0, 0.4, 4.0, 20.0, sensor,
                             {.sigma_xy_m = 0.01, .sigma_theta_rad = 0.001});
  EkfSlamParams params;
  params.schedule = UpdateSchedule::kPerScan;
  EkfSlam dense = drive.MakeFilter(EkfUpdateMode::kDense, params, MakePolicy(entropy));
  EkfSlam compressed = drive.MakeFilter(EkfUpdateMode::kCompressed, params, MakePolicy(entropy));
  std::vector<PointObservation> scan;
  int candidates = 0, applied = 0;
  for (int step = 1; step <= steps; ++step) {
    const Control u = drive.Step(scan);
    dense.Predict(u, 0.1);
    compressed.Predict(u, 0.1);
    const std::vector<AssociationDecision> expected = dense.Update(scan);
    const std::vector<AssociationDecision> got = compressed.Update(scan);
    testing::ExpectSameDecisions(got, expected, step);
    if (::testing::Test::HasFatalFailure()) return;
    ASSERT_EQ(compressed.LastSelectionStats().applied, dense.LastSelectionStats().applied)
        << "step " << step;
    candidates += dense.LastSelectionStats().candidates;
    applied += dense.LastSelectionStats().applied;
  }
  EXPECT_LT(applied, candidates);  // the policy left sightings out
  EXPECT_GT(applied, candidates / 10);
  EXPECT_GT(compressed.Compression().global_updates, 0);
  compressed.Flush();
  EXPECT_LT(RelativeDiff(compressed.State(), dense.State()), 1e-9);
  EXPECT_LT(RelativeDiff(compressed.Covariance(), dense.Covariance()), 1e-9);
}

TEST(CompressedEkfSlam, TheCovariancePolicyMakesTheSameDecisions) { ExpectSameRun(false, 300); }

// The dense entropy policy costs O(n³) a sighting (and O(n²·a) to read the whole covariance
// through an open area): a shorter run.
TEST(CompressedEkfSlam, TheDenseEntropyPolicyMakesTheSameDecisions) { ExpectSameRun(true, 40); }

}  // namespace
}  // namespace slamkit
