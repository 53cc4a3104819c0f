#include "slamkit/filters/fastslam/fastslam.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "common/landmark_inputs.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/relative_point.hpp"

namespace slamkit {
namespace {

using testing::Odo;
using testing::RangeBearingObs;

FastSlam MakeFastSlam(FastSlamParams params) {
  return FastSlam(params, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>());
}

// The textbook EKF correction of one landmark seen from a known pose (Probabilistic Robotics
// Table 3.3, standard covariance form), written out independently of KalmanUpdate.
void DirectEkf(const Pose2& x, const PointObservation& obs, Eigen::Vector2d& m,
               Eigen::Matrix2d& P) {
  Eigen::Matrix2d H;
  const RangeBearing rb = PredictRangeBearing(x, m, nullptr, &H);
  Eigen::Vector2d nu = obs.z - Eigen::Vector2d(rb.range_m, rb.bearing_rad);
  nu[1] = WrapAngle(nu[1]);
  const Eigen::Matrix2d K = P * H.transpose() * (H * P * H.transpose() + obs.R).inverse();
  m += K * nu;
  P = (Eigen::Matrix2d::Identity() - K * H) * P;
}

class FastSlamProposals : public ::testing::TestWithParam<FastSlamProposal> {};

// With one particle, a known pose (no motion noise) and known association, FastSLAM is one EKF
// per landmark: its initialisation and corrections equal the direct 2×2 computation.
TEST_P(FastSlamProposals, OneParticleFixedPoseEqualsTheLandmarkEkf) {
  FastSlamParams params;
  params.particles = 1;
  params.known_association = true;
  params.proposal = GetParam();
  FastSlam slam = MakeFastSlam(params);
  Pose2 x(1.0, -2.0, 0.4);
  slam.Reset(x);
  const PointObservation first = RangeBearingObs(7.0, 0.3, 42);
  ASSERT_EQ(slam.Update({&first, 1})[0].kind, AssociationDecision::Kind::kNew);
  Eigen::Matrix2d J_l_z;
  Eigen::Vector2d m = InvertRangeBearing(x, {7.0, 0.3}, nullptr, &J_l_z);
  Eigen::Matrix2d P = J_l_z * first.R * J_l_z.transpose();
  const ControlCovariance no_noise = ControlCovariance::Zero(3, 3);
  const Control u = Odo(0.4, 0.05, 0.03);
  for (int k = 0; k < 5; ++k) {
    slam.Predict(u, 0.1, &no_noise);
    x = OdometryModel().Move(x, u, 0.1);
    const PointObservation obs = RangeBearingObs(6.8 - 0.3 * k, 0.2 - 0.02 * k, 42);
    const AssociationDecision d = slam.Update({&obs, 1})[0];
    EXPECT_EQ(d.kind, AssociationDecision::Kind::kMatched);
    EXPECT_EQ(d.landmark, 0);
    DirectEkf(x, obs, m, P);
  }
  const LandmarkMap map = slam.Map();
  ASSERT_EQ(map.landmarks.size(), 1u);
  EXPECT_LT((map.landmarks[0].position_m - m).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((map.landmarks[0].covariance - P).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT(PoseError(slam.PoseEstimate(), x).norm(), 1e-12);
  EXPECT_EQ(map.landmarks[0].source_id, 42);
}

INSTANTIATE_TEST_SUITE_P(Both, FastSlamProposals,
                         ::testing::Values(FastSlamProposal::kMotion,
                                           FastSlamProposal::kObservation));

// One noisy step of `n` particles towards a known landmark; the weights differ afterwards.
FastSlam OneWeightedStep(int n, double threshold, std::uint64_t seed, double q_xy = 0.05) {
  FastSlamParams params;
  params.particles = n;
  params.known_association = true;
  params.proposal = FastSlamProposal::kMotion;
  params.resampling.threshold = threshold;
  params.seed = seed;
  FastSlam slam = MakeFastSlam(params);
  slam.Reset(Pose2());
  const PointObservation first = RangeBearingObs(5.0, 0.5, 1);
  slam.Update({&first, 1});
  const ControlCovariance Q = Eigen::Vector3d(q_xy, q_xy, 0.2 * q_xy).asDiagonal();
  slam.Predict(Odo(1.0, 0.0, 0.0), 0.1, &Q);
  const PointObservation second = RangeBearingObs(4.2, 0.6, 1);
  slam.Update({&second, 1});
  return slam;
}

// FastSLAM's resampling keeps the weights normalised and is unbiased: a resampled particle set
// is, on average over the draw, the weighted set it replaced. With f(particle) = its weight before
// resampling, E[mean of f after] = Σ w² (a resampler favouring heavy particles gives more, one
// ignoring the weights 1/N). The schemes themselves are tested in resampling_test.cpp; this checks
// that the filter resamples the particles it weighted, with their weights, and copies them whole.
TEST(FastSlamResampling, WeightsNormalisedAndResampledSetUnbiased) {
  const int n = 20, seeds = 300;
  double sum_diff = 0.0, sum_diff2 = 0.0;
  for (int s = 0; s < seeds; ++s) {
    const FastSlam kept = OneWeightedStep(n, 0.0, s);        // never resamples
    const FastSlam resampled = OneWeightedStep(n, 2.0, s);  // always resamples
    ASSERT_FALSE(kept.last_update_resampled());
    ASSERT_TRUE(resampled.last_update_resampled());
    const std::vector<double> w = kept.Weights();
    double total = 0.0, sum_w2 = 0.0, mean_after = 0.0;
    for (double wi : w) total += wi, sum_w2 += wi * wi;
    ASSERT_NEAR(total, 1.0, 1e-12);
    for (int j = 0; j < n; ++j) {
      const int source = resampled.particles().source(j);
      ASSERT_EQ(PoseError(resampled.particles()[j].pose, kept.particles()[source].pose).norm(), 0.0);
      ASSERT_NEAR(resampled.Weights()[j], 1.0 / n, 1e-12);
      mean_after += w[source] / n;
    }
    sum_diff += mean_after - sum_w2;
    sum_diff2 += (mean_after - sum_w2) * (mean_after - sum_w2);
  }
  const double mean = sum_diff / seeds;
  const double standard_error = std::sqrt((sum_diff2 / seeds - mean * mean) / seeds);
  EXPECT_GT(standard_error, 0.0);
  EXPECT_LT(std::abs(mean), 4.0 * standard_error) << mean << " ± " << standard_error;
}

// Resampling runs exactly when N_eff / N falls below the threshold.
TEST(FastSlamResampling, ResamplesOnlyBelowTheThreshold) {
  int resampled = 0;
  for (int s = 0; s < 50; ++s) {
    const FastSlam slam = OneWeightedStep(20, 0.5, s, 0.003);  // N_eff about N / 2
    const bool below = slam.particles().last_neff() < 0.5 * 20;
    EXPECT_EQ(slam.last_update_resampled(), below) << s;
    resampled += below;
  }
  EXPECT_GT(resampled, 0);
  EXPECT_LT(resampled, 50);
}

// After a scan that resampled, the pose estimate and covariance are those of the weighted set
// before resampling (the copies of a few ancestors would understate the spread), until the next
// prediction moves the resampled set.
TEST(FastSlamResampling, EstimateIsTheWeightedSetsBeforeResampling) {
  for (std::uint64_t s = 0; s < 5; ++s) {
    const FastSlam kept = OneWeightedStep(10, 0.0, s, 0.003);
    FastSlam resampled = OneWeightedStep(10, 2.0, s, 0.003);
    ASSERT_TRUE(resampled.last_update_resampled());
    EXPECT_TRUE(resampled.PoseEstimate().vector().isApprox(kept.PoseEstimate().vector(), 1e-12));
    EXPECT_TRUE(resampled.PoseCovariance().isApprox(kept.PoseCovariance(), 1e-12));
    const ControlCovariance Q = Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal();
    resampled.Predict(Odo(0.0, 0.0, 0.0), 0.1, &Q);
    EXPECT_FALSE(resampled.PoseCovariance().isApprox(kept.PoseCovariance(), 1e-6));
  }
}

// Resampling copies particles without copying their maps: a step that updates one landmark adds
// about one path per particle to the memory the set holds, not a map.
TEST(FastSlamMemory, ResamplingSharesTheParticlesMaps) {
  FastSlamParams params;
  params.particles = 50;
  params.known_association = true;
  params.resampling.threshold = 2.0;
  FastSlam slam = MakeFastSlam(params);
  slam.Reset(Pose2());
  LandmarkMap prior;
  for (int i = 0; i < 1000; ++i) {
    prior.landmarks.push_back({i, Eigen::Vector2d(0.1 * i, 3.0), 0.01 * Eigen::Matrix2d::Identity()});
  }
  slam.AddLandmarks(prior);
  auto bytes = [&] {
    std::vector<const LandmarkTree<FastSlamLandmark>*> trees;
    for (int k = 0; k < slam.particles().size(); ++k) trees.push_back(&slam.particles()[k].landmarks);
    return LandmarkTree<FastSlamLandmark>::CountDistinctNodes(trees).bytes();
  };
  const std::size_t one_map = bytes();
  const ControlCovariance Q = Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal();
  slam.Predict(Odo(0.1, 0.0, 0.0), 0.1, &Q);
  const PointObservation obs = RangeBearingObs(3.0, 1.57, 0);
  slam.Update({&obs, 1});
  ASSERT_TRUE(slam.last_update_resampled());
  using Tree = LandmarkTree<FastSlamLandmark>;
  const std::size_t path_bytes = Tree::LeafBytes() + 10 * Tree::BranchBytes();  // log₂ 1024
  EXPECT_LE(bytes(), one_map + 50 * path_bytes);
  EXPECT_GT(bytes(), one_map);
  EXPECT_THROW(slam.AddLandmarks(prior), std::logic_error);
}

// The new-landmark test. A landmark known only to 5 m (σ) is predicted so broadly that the density
// of even an exact sighting stays below p0 (Montemerlo's test creates a duplicate), while its
// squared Mahalanobis distance is 0 (the EKF's test matches it); with that test a sighting
// between the gates is dropped and one beyond new_landmark_chi2 is new.
TEST(FastSlamAssociation, NewLandmarkTestsDecideByDensityOrByDistance) {
  const auto decide = [](NewLandmarkTest test, double range_m) {
    FastSlamParams params;
    params.particles = 1;
    params.new_landmark_test = test;
    FastSlam slam = MakeFastSlam(params);
    slam.Reset(Pose2());
    LandmarkMap prior;
    prior.landmarks.push_back(
        {kNoLandmark, Eigen::Vector2d(5.0, 0.0), 25.0 * Eigen::Matrix2d::Identity()});
    slam.AddLandmarks(prior);
    const PointObservation obs = RangeBearingObs(range_m, 0.0);
    return slam.Update({&obs, 1}).at(0).kind;
  };
  using Kind = AssociationDecision::Kind;
  EXPECT_EQ(decide(NewLandmarkTest::kLikelihood, 5.0), Kind::kNew);
  EXPECT_EQ(decide(NewLandmarkTest::kMahalanobis, 5.0), Kind::kMatched);
  EXPECT_EQ(decide(NewLandmarkTest::kMahalanobis, 22.0), Kind::kDropped);  // d² ≈ 17² / 25 = 11.6
  EXPECT_EQ(decide(NewLandmarkTest::kMahalanobis, 25.0), Kind::kNew);      // d² ≈ 16
}

// Without association given, a re-sighting of a landmark matches it and a far sighting starts a
// new one; indexes are stable and every decision names a landmark of Map().
TEST(FastSlamAssociation, MaximumLikelihoodMatchesAndCreates) {
  FastSlamParams params;
  params.particles = 10;
  FastSlam slam = MakeFastSlam(params);
  slam.Reset(Pose2());
  const std::vector<PointObservation> first = {RangeBearingObs(5.0, 0.5), RangeBearingObs(8.0, -1.0)};
  const std::vector<AssociationDecision> d0 = slam.Update(first);
  ASSERT_EQ(d0.size(), 2u);
  EXPECT_EQ(d0[0].kind, AssociationDecision::Kind::kNew);
  EXPECT_EQ(d0[1].kind, AssociationDecision::Kind::kNew);
  EXPECT_NE(d0[0].landmark, d0[1].landmark);
  const std::vector<PointObservation> second = {RangeBearingObs(8.01, -1.001),
                                                RangeBearingObs(5.0, 2.5)};
  const std::vector<AssociationDecision> d1 = slam.Update(second);
  EXPECT_EQ(d1[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d1[0].landmark, d0[1].landmark);
  EXPECT_EQ(d1[1].kind, AssociationDecision::Kind::kNew);
  EXPECT_EQ(slam.NumLandmarks(), 3);
  EXPECT_NO_THROW(slam.CheckOutputHealth());
}

// A sensor without a range limit (the relative-point model of an iSAM log) makes the search
// radius infinite: every landmark is a candidate, and a re-sighting still matches.
TEST(FastSlamAssociation, AnUnboundedSensorStillFindsItsLandmarks) {
  FastSlamParams params;
  params.particles = 10;
  FastSlam slam(params, std::make_unique<OdometryModel>(), std::make_unique<RelativePointModel>());
  slam.Reset(Pose2());
  PointObservation near, far;
  near.z << 5.0, 1.0;
  far.z << 40.0, -30.0;
  near.R = far.R = 0.01 * Eigen::Matrix2d::Identity();
  const std::vector<PointObservation> first = {near, far};
  const std::vector<AssociationDecision> d0 = slam.Update(first);
  const std::vector<PointObservation> again = {far, near};
  const std::vector<AssociationDecision> d1 = slam.Update(again);
  ASSERT_EQ(d1.size(), 2u);
  EXPECT_EQ(d1[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d1[0].landmark, d0[1].landmark);
  EXPECT_EQ(d1[1].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d1[1].landmark, d0[0].landmark);
  EXPECT_EQ(slam.NumLandmarks(), 2);
}

// Negative evidence: a landmark in view that is never seen again is removed (and kept without it).
TEST(FastSlamAssociation, NegativeEvidenceRemovesUnseenLandmarks) {
  for (bool negative : {false, true}) {
    FastSlamParams params;
    params.particles = 5;
    params.negative_evidence = negative;
    FastSlam slam = MakeFastSlam(params);
    slam.Reset(Pose2());
    const std::vector<PointObservation> first = {RangeBearingObs(5.0, 0.5), RangeBearingObs(9.0, -1.0)};
    slam.Update(first);
    const PointObservation only = RangeBearingObs(5.0, 0.5);
    for (int k = 0; k < 3; ++k) slam.Update({&only, 1});
    for (int k = 0; k < slam.particles().size(); ++k) {
      EXPECT_EQ(slam.particles()[k].landmarks.size(), negative ? 1 : 2);
    }
  }
}

TEST(FastSlam, RejectsNonFiniteInputs) {
  FastSlam slam = MakeFastSlam({});
  EXPECT_THROW(slam.Predict(Odo(NAN, 0.0, 0.0), 0.1), std::invalid_argument);
  const PointObservation bad = RangeBearingObs(INFINITY, 0.0);
  EXPECT_THROW(slam.Update({&bad, 1}), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
