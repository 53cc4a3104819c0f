#include "slamkit/eval/landmark_smoother.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "slamkit/core/rng.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

// A drive twice around a circle of radius 20 m among a ring of landmarks, with noisy odometry
// (σ 0.05 m, 0.01 rad a step) and sightings (σ 0.1 m) of the landmarks within 12 m; the noise
// drawn is `noise` times those (the covariances stay).
struct Log {
  std::vector<Pose2> truth;
  std::vector<Pose2> dead_reckoning;
  std::vector<SmootherOdometry> odometry;
  std::vector<SmootherSighting> sightings;
  std::vector<Eigen::Vector2d> landmarks;
};

Log MakeLog(double noise) {
  constexpr double kOdometrySigmaM = 0.05, kOdometrySigmaRad = 0.01, kSightingSigmaM = 0.1;
  Rng rng(11);
  Log log;
  for (int i = 0; i < 24; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 24.0;
    const double r = i % 2 == 0 ? 14.0 : 26.0;
    log.landmarks.emplace_back(r * std::cos(a), r * std::sin(a) + 20.0);
  }
  const double turn = 2.0 * std::numbers::pi / 60.0;
  const Pose2 step(2.0 * 20.0 * std::sin(0.5 * turn), 0.0, turn);
  log.truth.push_back(Pose2());
  log.dead_reckoning.push_back(Pose2());
  for (int k = 0; k < 120; ++k) {
    const Eigen::Vector3d e =
        noise * testing::NormalVector3(rng, kOdometrySigmaM, kOdometrySigmaM, kOdometrySigmaRad);
    const Pose2 measured(step.x() + e.x(), step.y() + e.y(), step.theta() + e.z());
    const Eigen::Vector3d sigmas(kOdometrySigmaM, kOdometrySigmaM, kOdometrySigmaRad);
    log.odometry.push_back({k, k + 1, measured, sigmas.cwiseAbs2().asDiagonal()});
    log.truth.push_back(log.truth.back().Compose(step));
    log.dead_reckoning.push_back(log.dead_reckoning.back().Compose(measured));
  }
  for (int k = 0; k < static_cast<int>(log.truth.size()); ++k) {
    for (int id = 0; id < static_cast<int>(log.landmarks.size()); ++id) {
      const Eigen::Vector2d local = log.truth[k].TransformTo(log.landmarks[id]);
      if (local.norm() > 12.0) continue;
      const Eigen::Vector2d z = local + noise * testing::NormalVector2(rng, kSightingSigmaM, kSightingSigmaM);
      log.sightings.push_back(
          {k, id, z, kSightingSigmaM * kSightingSigmaM * Eigen::Matrix2d::Identity()});
    }
  }
  return log;
}

double PositionRms(const std::vector<Pose2>& a, const std::vector<Pose2>& b) {
  double sum = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    sum += (a[k].translation() - b[k].translation()).squaredNorm();
  }
  return std::sqrt(sum / a.size());
}

TEST(SmoothLandmarkSlam, RecoversExactMeasurementsFromAPerturbedStart) {
  const Log log = MakeLog(0.0);
  std::vector<Pose2> start = log.truth;
  Rng rng(3);
  for (std::size_t k = 1; k < start.size(); ++k) {
    const Eigen::Vector3d e = testing::NormalVector3(rng, 0.3, 0.3, 0.03);
    start[k] = Pose2(start[k].x() + e.x(), start[k].y() + e.y(), start[k].theta() + e.z());
  }
  const LandmarkSmootherResult r = SmoothLandmarkSlam(start, log.odometry, log.sightings);
  ASSERT_TRUE(r.converged);
  EXPECT_LT(PositionRms(r.poses, log.truth), 1e-6);
  for (const auto& [id, p] : r.landmarks) EXPECT_LT((p - log.landmarks[id]).norm(), 1e-6) << id;
}

TEST(SmoothLandmarkSlam, BeatsDeadReckoningAndIsConsistent) {
  const Log log = MakeLog(1.0);
  const LandmarkSmootherResult r =
      SmoothLandmarkSlam(log.dead_reckoning, log.odometry, log.sightings);
  ASSERT_TRUE(r.converged);
  const double dead_reckoning = PositionRms(log.dead_reckoning, log.truth);
  const double smoothed = PositionRms(r.poses, log.truth);
  EXPECT_GT(dead_reckoning, 0.5);
  EXPECT_LT(smoothed, 0.2 * dead_reckoning) << smoothed << " vs " << dead_reckoning;
  // χ² of the residuals at the optimum has (residuals − unknowns) degrees of freedom: within
  // ±4 of its standard deviation √(2 dof) when the covariances describe the noise.
  const int unknowns = 3 * (static_cast<int>(r.poses.size()) - 1) +
                       2 * static_cast<int>(r.landmarks.size());
  const double dof = r.residuals - unknowns;
  EXPECT_NEAR(r.chi2, dof, 4.0 * std::sqrt(2.0 * dof));
}

void ExpectError(const std::vector<Pose2>& poses, const std::vector<SmootherOdometry>& odometry,
                 const std::vector<SmootherSighting>& sightings, const std::string& what) {
  try {
    SmoothLandmarkSlam(poses, odometry, sightings);
    ADD_FAILURE() << "no error; expected " << what;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

TEST(SmoothLandmarkSlam, NamesWhatIsWrongWithItsInput) {
  const Log log = MakeLog(1.0);
  std::vector<SmootherOdometry> odometry = log.odometry;
  odometry[5].to = 500;
  ExpectError(log.dead_reckoning, odometry, log.sightings, "odometry names pose 500 of 121");
  odometry = log.odometry;
  odometry.erase(odometry.begin() + 7, odometry.begin() + 9);  // pose 8 loses both its links
  ExpectError(log.dead_reckoning, odometry, log.sightings, "no odometry constrains pose 8");
  odometry = log.odometry;
  odometry[3].covariance(2, 2) = -1.0;
  ExpectError(log.dead_reckoning, odometry, log.sightings,
              "odometry 3 -> 4: covariance not positive definite");
  std::vector<SmootherSighting> sightings = log.sightings;
  sightings[0].covariance.setZero();
  ExpectError(log.dead_reckoning, log.odometry, sightings, "covariance not positive definite");
  ExpectError({}, {}, {}, "no poses");
}

}  // namespace
}  // namespace slamkit
