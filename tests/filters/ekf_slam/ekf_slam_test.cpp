#include "slamkit/filters/ekf_slam/ekf_slam.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "common/landmark_inputs.hpp"
#include "common/numeric_jacobian.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/relative_point.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

using testing::Odo;
using testing::RangeBearingObs;

// A filter with a few correlated landmarks, built through the public operations only.
EkfSlam MakeBusyFilter(int landmarks, std::uint64_t seed) {
  EkfSlamParams params;
  params.initial_landmark_capacity = 2;  // forces the state to grow while landmarks are added
  EkfSlam slam(params, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>());
  slam.Reset(Pose2(1.0, -2.0, 0.4), Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal());
  Rng rng(seed);
  for (int i = 0; i < landmarks; ++i) {
    const Eigen::Vector2d z = testing::UniformVector2(rng, 2.0, 20.0, -3.0, 3.0);
    slam.AddLandmark(RangeBearingObs(z.x(), z.y(), i));
    slam.Predict(Odo(0.5, 0.05, 0.1), 0.1);
  }
  return slam;
}

TEST(EkfSlam, SequentialUpdateEqualsDenseTextbookUpdate) {
  EkfSlam slam = MakeBusyFilter(6, 1);
  const Eigen::VectorXd x = slam.State();
  const Eigen::MatrixXd P = slam.Covariance();
  const int n = slam.StateSize(), landmark = 3, c = 3 + 2 * landmark;
  const PointObservation obs = RangeBearingObs(7.0, 0.2);

  Eigen::Matrix<double, 2, 3> H_x;
  Eigen::Matrix2d H_l;
  const RangeBearing rb =
      PredictRangeBearing(slam.pose(), slam.LandmarkPosition(landmark), &H_x, &H_l);
  const Eigen::Vector2d z_pred(rb.range_m, rb.bearing_rad);
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, n);
  H.leftCols(3) = H_x;
  H.middleCols(c, 2) = H_l;
  const Eigen::MatrixXd S = H * P * H.transpose() + obs.R;
  const Eigen::MatrixXd K = P * H.transpose() * S.inverse();
  Eigen::Vector2d nu = obs.z - z_pred;
  nu[1] = WrapAngle(nu[1]);
  Eigen::VectorXd x_expected = x + K * nu;
  x_expected[2] = WrapAngle(x_expected[2]);
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
  const Eigen::MatrixXd P_expected =
      (I - K * H) * P * (I - K * H).transpose() + K * obs.R * K.transpose();

  slam.UpdateLandmark(landmark, obs);
  EXPECT_LT((slam.State() - x_expected).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((slam.Covariance() - P_expected).cwiseAbs().maxCoeff(), 1e-9);
}

TEST(EkfSlam, PredictionEqualsDenseJacobianForm) {
  EkfSlam slam = MakeBusyFilter(4, 2);
  const Eigen::MatrixXd P = slam.Covariance();
  const int n = slam.StateSize();
  const Control u = Odo(0.3, -0.1, 0.05);
  const OdometryModel model;
  Eigen::Matrix3d F_v;
  ControlJacobian G;
  const Pose2 moved = model.Move(slam.pose(), u, 0.1, &F_v, &G);
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(n, n);
  F.topLeftCorner<3, 3>() = F_v;
  Eigen::MatrixXd P_expected = F * P * F.transpose();
  P_expected.topLeftCorner<3, 3>() += G * model.Noise(u, 0.1) * G.transpose();

  slam.Predict(u, 0.1);
  EXPECT_LT((slam.pose().vector() - moved.vector()).norm(), 1e-12);
  EXPECT_LT((slam.Covariance() - P_expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(EkfSlam, AugmentationEqualsDenseJacobianForm) {
  EkfSlam slam = MakeBusyFilter(5, 3);
  const Eigen::MatrixXd P = slam.Covariance();
  const int n = slam.StateSize();
  const PointObservation obs = RangeBearingObs(4.0, -0.7);
  Eigen::Matrix<double, 2, 3> G_x;
  Eigen::Matrix2d G_z;
  const Eigen::Vector2d l = InvertRangeBearing(slam.pose(), {4.0, -0.7}, &G_x, &G_z);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n + 2, n + 2);
  J.topLeftCorner(n, n).setIdentity();
  J.block(n, 0, 2, 3) = G_x;
  J.block(n, n, 2, 2) = G_z;
  Eigen::MatrixXd P_aug = Eigen::MatrixXd::Zero(n + 2, n + 2);
  P_aug.topLeftCorner(n, n) = P;
  P_aug.bottomRightCorner(2, 2) = obs.R;

  const int index = slam.AddLandmark(obs);
  EXPECT_EQ(index, 5);
  EXPECT_TRUE(slam.LandmarkPosition(index).isApprox(l, 1e-12));
  EXPECT_LT((slam.Covariance() - J * P_aug * J.transpose()).cwiseAbs().maxCoeff(), 1e-12);
}

// With the heading known exactly and fixed at zero, odometry and relative-point sightings are
// linear in the state, so the EKF must reproduce a textbook Kalman filter.
TEST(EkfSlam, EqualsKalmanFilterOnLinearGaussianCase) {
  OdometryParams odo;
  odo.sigma_xy_m = 0.1;
  odo.sigma_theta_rad = 0.0;
  EkfSlamParams params;
  params.association_method = AssociationMethod::kKnown;
  EkfSlam slam(params, std::make_unique<OdometryModel>(odo), std::make_unique<RelativePointModel>());
  slam.Reset(Pose2(), Eigen::Vector3d(0.2, 0.3, 0.0).asDiagonal());

  const std::vector<Eigen::Vector2d> truth = {{3, 1}, {-2, 4}, {5, -3}};
  Eigen::Matrix2d R;
  R << 0.04, 0.01, 0.01, 0.09;
  Rng rng(12);
  // Reference Kalman filter over [x, y, l_1 … l_3] (heading dropped: it is exactly 0).
  Eigen::VectorXd m = Eigen::VectorXd::Zero(2);
  Eigen::MatrixXd C = Eigen::Vector2d(0.2, 0.3).asDiagonal();
  Eigen::Vector2d robot(0, 0);
  for (int step = 0; step < 20; ++step) {
    const Eigen::Vector2d d(0.4, 0.1 * (step % 3));
    robot += d;
    const Eigen::Vector2d noisy = d + testing::NormalVector2(rng, 0.1, 0.1);
    slam.Predict(Odo(noisy.x(), noisy.y(), 0.0), 1.0);
    m.head<2>() += noisy;
    C.topLeftCorner<2, 2>() += 0.01 * Eigen::Matrix2d::Identity();
    for (int k = 0; k < 3; ++k) {
      PointObservation obs;
      obs.z = truth[k] - robot + testing::NormalVector2(rng, 0.2, 0.3);
      obs.R = R;
      obs.id = k;
      const int col = 2 + 2 * k;
      if (col >= m.size()) {  // augmentation: l = t + z
        const int n = static_cast<int>(m.size());
        Eigen::MatrixXd J = Eigen::MatrixXd::Zero(n + 2, n + 2);
        J.topLeftCorner(n, n).setIdentity();
        J.block(n, 0, 2, 2).setIdentity();
        J.block(n, n, 2, 2).setIdentity();
        Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 2, n + 2);
        A.topLeftCorner(n, n) = C;
        A.bottomRightCorner(2, 2) = R;
        m.conservativeResize(n + 2);
        m.tail<2>() = m.head<2>() + obs.z;
        C = J * A * J.transpose();
      } else {
        Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, m.size());
        H.leftCols(2) = -Eigen::Matrix2d::Identity();
        H.middleCols(col, 2) = Eigen::Matrix2d::Identity();
        const Eigen::MatrixXd S = H * C * H.transpose() + R;
        const Eigen::MatrixXd K = C * H.transpose() * S.inverse();
        m += K * (obs.z - H * m);
        C = (Eigen::MatrixXd::Identity(m.size(), m.size()) - K * H) * C;
      }
      slam.Update(std::span(&obs, 1));
    }
    Eigen::VectorXd ekf_mean(m.size());
    ekf_mean << slam.State().head<2>(), slam.State().tail(m.size() - 2);
    Eigen::MatrixXd full = slam.Covariance();
    std::vector<int> keep = {0, 1};
    for (int i = 3; i < slam.StateSize(); ++i) keep.push_back(i);
    EXPECT_LT((ekf_mean - m).cwiseAbs().maxCoeff(), 1e-9) << "step " << step;
    EXPECT_LT((full(keep, keep) - C).cwiseAbs().maxCoeff(), 1e-9) << "step " << step;
  }
}

TEST(EkfSlam, KnownAssociationUsesIdsAndUnknownFindsThem) {
  for (const bool known : {true, false}) {
    EkfSlamParams params;
    params.association_method =
        known ? AssociationMethod::kKnown : AssociationMethod::kNearestNeighbour;
    EkfSlam slam(params, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>());
    slam.Reset(Pose2(), Eigen::Matrix3d::Identity() * 1e-6);
    const std::vector<PointObservation> first = {RangeBearingObs(5.0, 0.3, 10),
                                                 RangeBearingObs(8.0, -1.0, 20)};
    const auto d1 = slam.Update(first);
    ASSERT_EQ(d1[0].kind, AssociationDecision::Kind::kNew);
    ASSERT_EQ(d1[1].kind, AssociationDecision::Kind::kNew);
    const std::vector<PointObservation> again = {RangeBearingObs(8.01, -1.001, 20),
                                                 RangeBearingObs(5.02, 0.301, 10)};
    const auto d2 = slam.Update(again);
    EXPECT_EQ(d2[0].kind, AssociationDecision::Kind::kMatched);
    EXPECT_EQ(d2[0].landmark, 1);
    EXPECT_EQ(d2[1].landmark, 0);
    EXPECT_EQ(slam.NumLandmarks(), 2);
    EXPECT_EQ(slam.LandmarkSourceId(1), 20);
  }
}

TEST(EkfSlam, RejectsNonFiniteObservation) {
  EkfSlam slam(EkfSlamParams{}, std::make_unique<OdometryModel>(),
               std::make_unique<RangeBearingModel>());
  const std::vector<PointObservation> bad = {RangeBearingObs(std::nan(""), 0.1)};
  EXPECT_THROW(slam.Update(bad), std::invalid_argument);
}

// What a joint-compatibility associator sees: for a hypothesis, the stacked innovation and
// H P Hᵀ + R over all its pairings, cross terms included.
class JointRecorder final : public Associator {
 public:
  std::vector<AssociationDecision> Associate(const AssociationContext& scan) override {
    const std::vector<Pairing> hypothesis = {{0, 2}, {1, 0}};
    joint = scan.Joint(hypothesis);
    return KnownAssociation().Associate(scan);
  }
  JointInnovation joint;
};

TEST(EkfSlam, AssociatorSeesTheJointInnovationOfAHypothesis) {
  EkfSlamParams params;
  params.schedule = UpdateSchedule::kPerScan;
  auto recorder = std::make_unique<JointRecorder>();
  JointRecorder* joint = recorder.get();
  EkfSlam slam(params, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>(),
               std::move(recorder));
  slam.Reset(Pose2(1.0, -2.0, 0.4), Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal());
  for (int i = 0; i < 3; ++i) slam.AddLandmark(RangeBearingObs(4.0 + i, -1.0 + i, i));
  slam.Predict(Odo(0.5, 0.05, 0.1), 0.1);
  const Eigen::VectorXd x = slam.State();
  const Eigen::MatrixXd P = slam.Covariance();
  const std::vector<PointObservation> scan = {RangeBearingObs(6.1, 0.9, 2),
                                              RangeBearingObs(3.9, -1.1, 0)};
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(4, x.size());
  Eigen::VectorXd nu(4);
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(4, 4);
  const int landmark_of[] = {2, 0};
  for (int k = 0; k < 2; ++k) {
    Eigen::Matrix<double, 2, 3> H_x;
    Eigen::Matrix2d H_l;
    const int c = 3 + 2 * landmark_of[k];
    const RangeBearing rb = PredictRangeBearing(Pose2(x.head<3>()), x.segment<2>(c), &H_x, &H_l);
    H.block(2 * k, 0, 2, 3) = H_x;
    H.block(2 * k, c, 2, 2) = H_l;
    nu.segment<2>(2 * k) = scan[k].z - Eigen::Vector2d(rb.range_m, rb.bearing_rad);
    nu[2 * k + 1] = WrapAngle(nu[2 * k + 1]);
    R.block<2, 2>(2 * k, 2 * k) = scan[k].R;
  }
  slam.Update(scan);
  EXPECT_LT((joint->joint.nu - nu).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((joint->joint.S - (H * P * H.transpose() + R)).cwiseAbs().maxCoeff(), 1e-12);
}

}  // namespace
}  // namespace slamkit
