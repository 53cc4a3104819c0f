#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "common/landmark_inputs.hpp"
#include "circle_drive.hpp"
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
using testing::Delayed;
using testing::Drive;
using testing::MakeDrive;

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
