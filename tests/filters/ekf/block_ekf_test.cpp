// The block-structured EKF behind the point-landmark filter against the dense textbook
// sequential EKF: a whole scan in one deferred step, a landmark update that defers its
// downdate, and the marginal of a few blocks. The test-only kinds: block_ekf_kinds_test.cpp.

#include "slamkit/filters/ekf/block_ekf.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Dense>
#include <unordered_map>

#include "block_ekf_kinds.hpp"
#include "common/landmark_inputs.hpp"
#include "common/ordered_draws.hpp"
#include "filters/dense_reference.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

using block_ekf_kinds::DenseEkf;
using block_ekf_kinds::Jacobians;
using block_ekf_kinds::MaxAbsDiff;
using block_ekf_kinds::Means;
using block_ekf_kinds::RangeBearingEval;
using testing::Odo;
using testing::RangeBearingObs;

// ---- The point-landmark filter, many observations in one deferred step. ----

// A filter of `landmarks` correlated landmarks, all with id = index (known association).
EkfSlam MakeLargeFilter(int landmarks) {
  EkfSlamParams params;
  params.association_method = AssociationMethod::kKnown;
  params.initial_landmark_capacity = 8;  // forces growth, also in the middle of the scan below
  EkfSlam slam(params, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>());
  slam.Reset(Pose2(1.0, -2.0, 0.4), Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal());
  Rng rng(21);
  for (int i = 0; i < landmarks; ++i) {
    const Eigen::Vector2d z = testing::UniformVector2(rng, 2.0, 25.0, -3.0, 3.0);
    slam.AddLandmark(RangeBearingObs(z.x(), z.y(), i));
    if (i % 10 == 0) slam.Predict(Odo(0.5, 0.05, 0.1), 0.1);
  }
  return slam;
}

// 40 sightings: two in three of mapped landmarks, the rest new ones interleaved.
std::vector<PointObservation> MixedScan(const EkfSlam& slam, int landmarks) {
  Rng rng(22);
  std::vector<PointObservation> scan;
  for (int k = 0; k < 40; ++k) {
    if (k % 3 == 2) {
      const Eigen::Vector2d z = testing::UniformVector2(rng, 3.0, 20.0, -3.0, 3.0);
      scan.push_back(RangeBearingObs(z.x(), z.y(), 1000 + k));
      continue;
    }
    const int j = static_cast<int>(rng.Uniform(0.0, landmarks - 1e-9));
    const RangeBearing rb = PredictRangeBearing(slam.pose(), slam.LandmarkPosition(j));
    const Eigen::Vector2d e = testing::NormalVector2(rng, 0.1, 0.02);
    scan.push_back(RangeBearingObs(rb.range_m + e.x(), rb.bearing_rad + e.y(), j));
  }
  return scan;
}

// The dense textbook filter run on the same scan, observation by observation.
DenseEkf DenseRun(const EkfSlam& slam, const std::vector<PointObservation>& scan) {
  DenseEkf ref{slam.State(), slam.Covariance(), {2}};
  std::unordered_map<LandmarkId, int> offset;
  for (int i = 0; i < slam.NumLandmarks(); ++i) offset[slam.LandmarkSourceId(i)] = 3 + 2 * i;
  for (const PointObservation& obs : scan) {
    const Pose2 pose(ref.x.head<3>());
    const auto it = offset.find(obs.id);
    if (it == offset.end()) {
      Eigen::Matrix<double, 2, 3> G_x;
      Eigen::Matrix2d G_z;
      const Eigen::Vector2d l = InvertRangeBearing(pose, {obs.z[0], obs.z[1]}, &G_x, &G_z);
      offset[obs.id] = static_cast<int>(ref.x.size());
      ref.Augment(l, ref.Spread(G_x, 0), G_z, obs.R);
      continue;
    }
    const Means means = {ref.x.head<3>(), ref.x.segment<2>(it->second)};
    Jacobians J;
    const Eigen::VectorXd z_pred = RangeBearingEval(means, &J);
    Eigen::Vector2d nu = obs.z - z_pred;
    nu[1] = WrapAngle(nu[1]);
    ref.Update(nu, ref.Spread(J[0], 0) + ref.Spread(J[1], it->second), obs.R);
  }
  return ref;
}

TEST(BlockEkf, DeferredScanEqualsDenseSequentialEkfOnLargeState) {
  constexpr int kLandmarks = 140;  // n = 283: three fixed column blocks of the downdate
  std::vector<Eigen::MatrixXd> covariances;
  for (const int threads : {1, 2}) {
    const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    EkfSlam slam = MakeLargeFilter(kLandmarks);
    ASSERT_GT(slam.StateSize(), 256);
    const std::vector<PointObservation> scan = MixedScan(slam, kLandmarks);
    const DenseEkf ref = DenseRun(slam, scan);
    const std::vector<AssociationDecision> decisions = slam.Update(scan);
    for (std::size_t k = 0; k < scan.size(); ++k) {
      EXPECT_EQ(decisions[k].kind,
                k % 3 == 2 ? AssociationDecision::Kind::kNew : AssociationDecision::Kind::kMatched);
    }
    EXPECT_FALSE(slam.ekf().HasPendingDowndate());
    ASSERT_EQ(slam.StateSize(), ref.x.size());
    EXPECT_LT(MaxAbsDiff(slam.State(), ref.x), 1e-9) << threads << " threads";
    EXPECT_LT(MaxAbsDiff(slam.Covariance(), ref.P), 1e-9) << threads << " threads";
    covariances.push_back(slam.Covariance());
  }
  // Fixed column blocks: the thread count does not change a bit.
  EXPECT_TRUE(covariances[0] == covariances[1]);
}

TEST(BlockEkf, UpdateLandmarkDefersTheDowndate) {
  EkfSlam slam = MakeLargeFilter(20);
  std::vector<PointObservation> scan = MixedScan(slam, 20);
  std::erase_if(scan, [](const PointObservation& o) { return o.id >= 1000; });
  scan.resize(5);
  const DenseEkf ref = DenseRun(slam, scan);
  for (const PointObservation& obs : scan) slam.UpdateLandmark(static_cast<int>(obs.id), obs);
  EXPECT_TRUE(slam.ekf().HasPendingDowndate());
  EXPECT_LT(MaxAbsDiff(slam.State(), ref.x), 1e-9);
  EXPECT_LT(MaxAbsDiff(slam.Covariance(), ref.P), 1e-9);  // read through the pending downdate
  EXPECT_LT(MaxAbsDiff(slam.PoseCovariance(), ref.P.topLeftCorner<3, 3>()), 1e-9);
  slam.ApplyPendingDowndate();
  EXPECT_FALSE(slam.ekf().HasPendingDowndate());
  EXPECT_LT(MaxAbsDiff(slam.Covariance(), ref.P), 1e-9);
}

// The marginal of a few blocks holds their means and joint covariance (through a pending
// downdate), and an update touching only them leaves them as the whole filter's update does.
TEST(BlockEkf, MarginalIsTheBlocksJointGaussianAndUpdatesAsTheWholeFilter) {
  const RangeBearingModel sensor;
  BlockEkf ekf(8);
  const int point_kind = ekf.RegisterKind({2, {}, false});
  const PointLandmarkModel points(sensor, point_kind, 5.0);
  ekf.AddBlock(kPoseKind, Eigen::Vector3d(0.0, 0.0, 0.3),
               Eigen::Vector3d(0.1, 0.1, 0.01).asDiagonal());
  const Eigen::Matrix2d R = Eigen::Vector2d(0.05 * 0.05, 0.01 * 0.01).asDiagonal();
  const int pose[] = {0};
  std::vector<int> l;
  for (int i = 0; i < 5; ++i) {
    l.push_back(AugmentFrom(points, ekf, pose, Eigen::Vector2d(4.0 + i, 0.3 * i - 0.6), R));
  }
  const OdometryModel motion;
  Eigen::Matrix3d J_x;
  ControlJacobian J_u;
  const Pose2 moved = motion.Move(ekf.PoseOf(0), Odo(0.5, 0.1, 0.05), 1.0, &J_x, &J_u);
  ekf.PredictPose(0, moved, J_x, J_u, motion.Noise(Odo(0.5, 0.1, 0.05), 1.0));
  const int seen[] = {0, l[1]};
  ekf.Update(Linearise(points, ekf, seen, Eigen::Vector2d(3.9, -0.35), R));  // left pending
  ASSERT_TRUE(ekf.HasPendingDowndate());

  const std::vector<int> blocks = {l[3], 0, l[1]};
  BlockEkf m = ekf.Marginal(blocks);
  ASSERT_EQ(m.NumBlocks(), 3);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(m.BlockKindOf(i), ekf.BlockKindOf(blocks[i]));
    EXPECT_LT(MaxAbsDiff(m.Mean(i), ekf.Mean(blocks[i])), 1e-15);
    for (int j = 0; j < 3; ++j) {
      EXPECT_LT(MaxAbsDiff(m.CovarianceBlock(i, j), ekf.CovarianceBlock(blocks[i], blocks[j])),
                1e-15);
    }
  }
  const int full_blocks[] = {0, l[3]};
  const int marginal_blocks[] = {1, 0};
  const Eigen::Vector2d z(6.9, 0.25);
  ekf.Update(Linearise(points, ekf, full_blocks, z, R));
  m.Update(Linearise(points, m, marginal_blocks, z, R));
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(MaxAbsDiff(m.Mean(i), ekf.Mean(blocks[i])), 1e-12);
    for (int j = 0; j < 3; ++j) {
      EXPECT_LT(MaxAbsDiff(m.CovarianceBlock(i, j), ekf.CovarianceBlock(blocks[i], blocks[j])),
                1e-12);
    }
  }
}

}  // namespace
}  // namespace slamkit
