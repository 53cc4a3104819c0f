#include "slamkit/filters/ekf/first_estimates.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <vector>

#include "common/landmark_inputs.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

using testing::Odo;
using testing::RangeBearingObs;

constexpr double kDt = 0.1;

EkfSlam MakeFilter(JacobianEstimates jacobians) {
  EkfSlamParams params;
  params.jacobians = jacobians;
  EkfSlam slam(params, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>());
  slam.Reset(Pose2(1.0, -2.0, 0.4), Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal());
  slam.AddLandmark(RangeBearingObs(6.0, 0.5, 0));
  slam.AddLandmark(RangeBearingObs(9.0, -0.8, 1));
  slam.AddLandmark(RangeBearingObs(4.0, 2.0, 2));
  return slam;
}

// A sighting of `landmark` offset from its prediction, so that the update moves the estimates.
PointObservation OffsetSighting(const EkfSlam& slam, int landmark, double dr, double db) {
  const Eigen::Vector2d z =
      RangeBearingModel().Predict(slam.pose(), slam.LandmarkPosition(landmark));
  return RangeBearingObs(z[0] + dr, z[1] + db, landmark);
}

// The full-state Jacobian of one linearisation (2 × n).
Eigen::MatrixXd Dense(const Linearisation& lin, int n) {
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, n);
  for (const BlockJacobian& b : lin.H.view()) {
    const int col = b.block == 0 ? 0 : 3 + 2 * (b.block - 1);
    H.middleCols(col, b.J.cols()) = b.J;
  }
  return H;
}

TEST(FirstEstimatesEkf, UpdateJacobianIsAtScanPriorPoseAndFirstLandmarkEstimate) {
  for (const JacobianEstimates mode :
       {JacobianEstimates::kCurrent, JacobianEstimates::kFirstEstimates}) {
    EkfSlam slam = MakeFilter(mode);
    const Eigen::Vector2d first = slam.LandmarkPosition(1);
    slam.Predict(Odo(0.5, 0.05, 0.1), kDt);
    const Pose2 prior = slam.pose();
    // Earlier updates of the same scan move the pose and landmark 1.
    slam.UpdateLandmark(0, OffsetSighting(slam, 0, 0.3, 0.05));
    slam.UpdateLandmark(1, OffsetSighting(slam, 1, -0.4, 0.04));
    ASSERT_GT((slam.pose().translation() - prior.translation()).norm(), 1e-2);
    ASSERT_GT((slam.LandmarkPosition(1) - first).norm(), 1e-2);

    const PointObservation obs = OffsetSighting(slam, 1, 0.2, -0.03);
    const Linearisation lin = slam.UpdateLinearisation(1, obs);
    const bool fej = mode == JacobianEstimates::kFirstEstimates;
    Eigen::Matrix<double, 2, 3> J_z_x;
    Eigen::Matrix2d J_z_l;
    RangeBearingModel().Predict(fej ? prior : slam.pose(), fej ? first : slam.LandmarkPosition(1),
                                &J_z_x, &J_z_l);
    EXPECT_LT((lin.H.items[0].J - J_z_x).norm(), 1e-12);
    EXPECT_LT((lin.H.items[1].J - J_z_l).norm(), 1e-12);
    // The innovation is always against the current estimates.
    EXPECT_LT((Eigen::Vector2d(lin.innovation) - Eigen::Vector2d(0.2, -0.03)).norm(), 1e-9);
  }
}

// Huang, Mourikis, Roumeliotis 2008, Sec. IV: Φ's heading column is J·(p̂_{k+1|k} − p̂_{k|k−1}).
TEST(FirstEstimatesEkf, PredictionUsesThePreviousPredictedPosition) {
  EkfSlam slam = MakeFilter(JacobianEstimates::kFirstEstimates);
  slam.Predict(Odo(0.5, 0.05, 0.1), kDt);
  const Pose2 prior = slam.pose();
  slam.UpdateLandmark(0, OffsetSighting(slam, 0, 0.3, 0.05));
  slam.ApplyPendingDowndate();
  const Eigen::MatrixXd P = slam.Covariance();
  const int n = slam.StateSize();
  const Control u = Odo(0.8, -0.1, 0.2);
  const OdometryModel model;
  Eigen::Matrix3d F_v;
  ControlJacobian G;
  const Pose2 moved = model.Move(slam.pose(), u, kDt, &F_v, &G);
  const Eigen::Matrix3d F_current = F_v;
  const Eigen::Vector2d dp = moved.translation() - prior.translation();
  F_v(0, 2) = -dp.y();
  F_v(1, 2) = dp.x();
  ASSERT_GT((F_v - F_current).norm(), 1e-2);  // the update moved the pose
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(n, n);
  F.topLeftCorner<3, 3>() = F_v;
  Eigen::MatrixXd P_expected = F * P * F.transpose();
  P_expected.topLeftCorner<3, 3>() += G * model.Noise(u, kDt) * G.transpose();

  slam.Predict(u, kDt);
  EXPECT_LT((slam.pose().vector() - moved.vector()).norm(), 1e-12);
  EXPECT_LT((slam.Covariance() - P_expected).cwiseAbs().maxCoeff(), 1e-12);
}

// Huang, Mourikis, Roumeliotis 2008, Sec. III: the observability matrix of the linearised system,
// M = [H_1; H_2 Φ_1; H_3 Φ_2 Φ_1; …], from the Jacobians the filter uses, has a null space of
// dimension 3 (global x, y, rotation) with FEJ, of 2 with the current estimates.
int UnobservableDimension(JacobianEstimates mode) {
  EkfSlam slam = MakeFilter(mode);
  const int n = slam.StateSize();
  Pose2 prior = slam.pose();
  Eigen::MatrixXd Phi_product = Eigen::MatrixXd::Identity(n, n);
  std::vector<Eigen::MatrixXd> blocks;
  for (int k = 0; k < 4; ++k) {
    const Control u = Odo(0.6, 0.02, 0.15);
    Eigen::Matrix3d F_v;
    const Pose2 moved = OdometryModel().Move(slam.pose(), u, kDt, &F_v);
    if (mode == JacobianEstimates::kFirstEstimates)
      FirstEstimatesMotionJacobian(moved, prior, &F_v);
    Eigen::MatrixXd F = Eigen::MatrixXd::Identity(n, n);
    F.topLeftCorner<3, 3>() = F_v;
    if (k > 0) Phi_product = F * Phi_product;
    slam.Predict(u, kDt);
    prior = slam.pose();
    for (int l = 0; l < 3; ++l) {
      const PointObservation obs = OffsetSighting(slam, l, 0.2 * (l - 1), 0.04);
      blocks.push_back(Dense(slam.UpdateLinearisation(l, obs), n) * Phi_product);
      slam.UpdateLandmark(l, obs);
    }
    slam.ApplyPendingDowndate();
  }
  Eigen::MatrixXd M(2 * static_cast<int>(blocks.size()), n);
  for (std::size_t i = 0; i < blocks.size(); ++i) M.middleRows(2 * i, 2) = blocks[i];
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(M);
  const Eigen::VectorXd s = svd.singularValues();
  int null = 0;
  for (int i = 0; i < s.size(); ++i) null += s[i] < 1e-9 * s[0] ? 1 : 0;
  return null;
}

TEST(FirstEstimatesEkf, LinearisedSystemKeepsThreeUnobservableDirections) {
  EXPECT_EQ(UnobservableDimension(JacobianEstimates::kFirstEstimates), 3);
  EXPECT_EQ(UnobservableDimension(JacobianEstimates::kCurrent), 2);
}

}  // namespace
}  // namespace slamkit
