#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "common/landmark_inputs.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

using testing::Odo;
using testing::RangeBearingObs;

// A drive once around a circle of radius 20 m past trees on two rings (radius 12 and 28 m, 24 m
// or more apart along them), sighted within 14 m; odometry and sightings with noise, ids withheld.
struct Drive {
  std::vector<Control> controls;
  std::vector<std::vector<PointObservation>> scans;  // one per pose, the first before any move
  std::vector<Eigen::Vector2d> trees;
};

Drive MakeDrive(int steps, std::uint64_t seed) {
  Rng rng(seed);
  Drive d;
  for (int i = 0; i < 16; ++i) {
    const double a = 2.0 * std::numbers::pi * (i + 0.5 * (i % 2)) / 16.0;
    const double r = i % 2 == 0 ? 12.0 : 28.0;
    d.trees.emplace_back(r * std::sin(a), 20.0 - r * std::cos(a));
  }
  const double turn = 2.0 * std::numbers::pi / steps;
  const Control step = Odo(2.0 * 20.0 * std::sin(0.5 * turn), 0.0, turn);
  Pose2 truth;
  for (int k = 0; k <= steps; ++k) {
    std::vector<PointObservation> scan;
    for (const Eigen::Vector2d& tree : d.trees) {
      const RangeBearing rb = PredictRangeBearing(truth, tree);
      if (rb.range_m > 14.0) continue;
      const Eigen::Vector2d e = testing::NormalVector2(rng, 0.05, 0.01);
      scan.push_back(RangeBearingObs(rb.range_m + e.x(), WrapAngle(rb.bearing_rad + e.y())));
    }
    d.scans.push_back(scan);
    if (k == steps) break;
    truth = OdometryModel().Move(truth, step, 0.0);
    // Within the odometry model's default noise (4 cm, 0.01° a step).
    const Eigen::Vector3d e = testing::NormalVector3(rng, 0.03, 0.03, 1.5e-4);
    d.controls.push_back(Odo(step[0] + e.x(), e.y(), step[2] + e.z()));
  }
  return d;
}

FastSlamParams Delayed(int particles) {
  FastSlamParams p;
  p.particles = particles;
  p.delayed_sampling = true;
  p.new_landmark_test = NewLandmarkTest::kMahalanobis;
  return p;
}

// Through ground it has never seen, a particle with delayed sampling never draws: its pose and
// every tree it maps are one Gaussian, so a single particle is EKF-SLAM, step for step.
TEST(FastSlamDelayedSampling, ThroughNewGroundOneParticleIsTheEkf) {
  const Drive d = MakeDrive(90, 3);
  FastSlamParams params = Delayed(1);
  params.window_max_landmarks = 100;
  FastSlam fast(params, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>());
  EkfSlam ekf(EkfSlamParams{}, std::make_unique<OdometryModel>(),
              std::make_unique<RangeBearingModel>());
  fast.Reset(Pose2());
  ekf.Reset(Pose2());
  for (std::size_t k = 0; k < d.scans.size(); ++k) {
    if (k > 0) {
      fast.Predict(d.controls[k - 1], 0.1);
      ekf.Predict(d.controls[k - 1], 0.1);
    }
    const auto a = fast.Update(d.scans[k]);
    const auto b = ekf.Update(d.scans[k]);
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].kind, b[i].kind) << "pose " << k << " sighting " << i;
      EXPECT_EQ(a[i].landmark, b[i].landmark) << "pose " << k << " sighting " << i;
    }
    EXPECT_LT(PoseError(fast.PoseEstimate(), ekf.PoseEstimate()).norm(), 1e-6) << k;
    EXPECT_LT((fast.PoseCovariance() - ekf.PoseCovariance()).norm(), 1e-6) << k;
  }
  const LandmarkMap fm = fast.Map(), em = ekf.Map();
  ASSERT_EQ(fm.landmarks.size(), em.landmarks.size());
  EXPECT_EQ(em.landmarks.size(), d.trees.size());
  for (std::size_t j = 0; j < fm.landmarks.size(); ++j) {
    EXPECT_LT((fm.landmarks[j].position_m - em.landmarks[j].position_m).norm(), 1e-6) << j;
    EXPECT_LT((fm.landmarks[j].covariance - em.landmarks[j].covariance).norm(), 1e-6) << j;
  }
}

// When every scan sights a landmark the particles already hold (here a prior map), each draws
// its pose at every scan from the same Gaussian as FastSLAM 2.0: the two runs agree (to rounding:
// the window's update is the standard Kalman form, 2.0's proposal the Joseph form).
TEST(FastSlamDelayedSampling, OnMappedGroundItIsFastSlam2) {
  const Drive d = MakeDrive(90, 4);
  LandmarkMap prior;
  for (const Eigen::Vector2d& tree : d.trees) {
    prior.landmarks.push_back({kNoLandmark, tree, 0.01 * Eigen::Matrix2d::Identity()});
  }
  FastSlamParams standard = Delayed(20);
  standard.delayed_sampling = false;
  std::vector<std::unique_ptr<FastSlam>> runs;
  for (const FastSlamParams& p : {standard, Delayed(20)}) {
    runs.push_back(std::make_unique<FastSlam>(p, std::make_unique<OdometryModel>(),
                                              std::make_unique<RangeBearingModel>()));
    runs.back()->AddLandmarks(prior);
  }
  double worst = 0.0;
  for (std::size_t k = 0; k < d.scans.size(); ++k) {
    ASSERT_FALSE(d.scans[k].empty()) << "every pose must sight a tree";
    for (auto& run : runs) {
      if (k > 0) run->Predict(d.controls[k - 1], 0.1);
      run->Update(d.scans[k]);
    }
    for (int i = 0; i < 20; ++i) {
      const double e = PoseError(runs[0]->particles()[i].pose, runs[1]->particles()[i].pose).norm();
      worst = std::max(worst, e);
    }
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_EQ(runs[1]->NumLandmarks(), static_cast<int>(d.trees.size()));
}

int LandmarksMapped(LandmarkSlamFilter& slam, const Drive& d) {
  for (std::size_t k = 0; k < d.scans.size(); ++k) {
    if (k > 0) slam.Predict(d.controls[k - 1], 0.1);
    slam.Update(d.scans[k]);
  }
  return slam.NumLandmarks();
}

// Twenty particles that draw whenever they match a landmark of their tree close the loop as the
// EKF does, tree for tree, on every drive of eight (landmarks drawn from a window are filed and
// found again); FastSLAM 2.0 with as many particles duplicates more trees.
TEST(FastSlamDelayedSampling, ClosesTheLoopAsTheEkfDoes) {
  int standard_excess = 0, delayed_excess = 0;
  for (std::uint64_t seed = 3; seed < 11; ++seed) {
    const Drive d = MakeDrive(90, seed);
    EkfSlam ekf(EkfSlamParams{}, std::make_unique<OdometryModel>(),
                std::make_unique<RangeBearingModel>());
    FastSlam delayed(Delayed(20), std::make_unique<OdometryModel>(),
                     std::make_unique<RangeBearingModel>());
    FastSlamParams p = Delayed(20);
    p.delayed_sampling = false;
    FastSlam standard(p, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>());
    const int trees = static_cast<int>(d.trees.size());
    const int by_ekf = LandmarksMapped(ekf, d);
    const int by_delayed = LandmarksMapped(delayed, d);
    EXPECT_EQ(by_delayed, by_ekf) << "drive " << seed;
    delayed_excess += by_delayed - trees;
    standard_excess += LandmarksMapped(standard, d) - trees;
  }
  EXPECT_LT(delayed_excess, standard_excess);
}

TEST(FastSlamDelayedSampling, NeedsEachParticlesOwnAssociation) {
  FastSlamParams params = Delayed(5);
  params.known_association = true;
  EXPECT_THROW(FastSlam(params, std::make_unique<OdometryModel>(),
                        std::make_unique<RangeBearingModel>()),
               std::invalid_argument);
  params = Delayed(5);
  params.negative_evidence = true;
  EXPECT_THROW(FastSlam(params, std::make_unique<OdometryModel>(),
                        std::make_unique<RangeBearingModel>()),
               std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
