// The block-structured EKF against the dense textbook sequential EKF, on the kinds slamkit ships
// (a pose, point landmarks under range-bearing) and on kinds defined here only: a second pose
// with vehicle-vehicle and position-fix observations, and a (ρ, α) line landmark. None of them
// needs a change to the update code.

#include "slamkit/filters/ekf/block_ekf.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Dense>
#include <functional>
#include <numbers>

#include "common/landmark_inputs.hpp"
#include "common/numeric_jacobian.hpp"
#include "common/ordered_draws.hpp"
#include "filters/dense_reference.hpp"
#include "slamkit/filters/ekf/observation_model.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

using testing::DenseEkf;
using testing::MaxAbsDiff;
using Means = std::vector<Eigen::VectorXd>;
using Jacobians = std::vector<Eigen::MatrixXd>;

constexpr double kPi = std::numbers::pi;

using testing::Odo;
using testing::RangeBearingObs;

// ---- Test-only kinds and models, each defined by its math on the means of its blocks. ----

// An observation model given by z = h(means of its blocks); the filter side reads the means
// from the BlockEkf, the dense reference from its own vector.
class TestModel : public ObservationModel {
 public:
  virtual Eigen::VectorXd Eval(const Means& means, Jacobians* J) const = 0;
  virtual std::vector<int> AngleRows() const { return {}; }

  BlockPrediction Predict(const BlockEkf& ekf, std::span<const int> blocks) const override {
    Means means;
    for (const int b : blocks) means.push_back(ekf.Mean(b));
    Jacobians J;
    BlockPrediction p;
    p.z = Eval(means, &J);
    for (std::size_t i = 0; i < blocks.size(); ++i) p.J_z_blocks.Add(blocks[i], J[i]);
    return p;
  }
  BlockVector Innovation(const BlockVector& z, const BlockVector& z_pred) const override {
    BlockVector nu = z - z_pred;
    for (const int r : AngleRows()) nu[r] = WrapAngle(nu[r]);
    return nu;
  }
};

// Where pose B's position appears from pose A: z = R(θ_A)ᵀ (t_B − t_A) (a vehicle-vehicle
// sighting, SPEC S3).
class RelativePositionModel final : public TestModel {
 public:
  int MeasurementDim() const override { return 2; }
  Eigen::VectorXd Eval(const Means& means, Jacobians* J) const override {
    const Pose2 a(means[0]);
    Eigen::Matrix<double, 2, 3> J_z_a;
    Eigen::Matrix2d J_z_t;
    const Eigen::Vector2d z = a.TransformTo(means[1].head<2>(), &J_z_a, &J_z_t);
    Eigen::Matrix<double, 2, 3> J_z_b = Eigen::Matrix<double, 2, 3>::Zero();
    J_z_b.leftCols<2>() = J_z_t;
    if (J) *J = {J_z_a, J_z_b};
    return z;
  }
};

// A position fix of one pose (a GPS-like observation touching a single block).
class PositionFixModel final : public TestModel {
 public:
  int MeasurementDim() const override { return 2; }
  Eigen::VectorXd Eval(const Means& means, Jacobians* J) const override {
    Eigen::Matrix<double, 2, 3> J_z_x = Eigen::Matrix<double, 2, 3>::Zero();
    J_z_x.leftCols<2>().setIdentity();
    if (J) *J = {J_z_x};
    return means[0].head<2>();
  }
};

// The range alone to a point (a 1-D measurement: BlockEkf's dynamic-size path).
class RangeOnlyModel final : public TestModel {
 public:
  int MeasurementDim() const override { return 1; }
  Eigen::VectorXd Eval(const Means& means, Jacobians* J) const override {
    const Eigen::Vector2d d = means[1] - means[0].head<2>();
    const double r = d.norm();
    Eigen::Matrix<double, 1, 3> J_z_x;
    J_z_x << -d.x() / r, -d.y() / r, 0.0;
    if (J) *J = {J_z_x, Eigen::Matrix<double, 1, 2>(d.x() / r, d.y() / r)};
    return Eigen::Matrix<double, 1, 1>(r);
  }
};

// Pose B seen from pose A as a whole pose, A⁻¹ ∘ B (a 3-D measurement).
class RelativePoseModel final : public TestModel {
 public:
  int MeasurementDim() const override { return 3; }
  std::vector<int> AngleRows() const override { return {2}; }
  Eigen::VectorXd Eval(const Means& means, Jacobians* J) const override {
    const Pose2 a(means[0]), b(means[1]);
    Eigen::Matrix<double, 2, 3> J_t_a;
    Eigen::Matrix2d J_t_b;
    const Eigen::Vector2d t = a.TransformTo(b.translation(), &J_t_a, &J_t_b);
    Eigen::Matrix3d J_z_a = Eigen::Matrix3d::Zero(), J_z_b = Eigen::Matrix3d::Zero();
    J_z_a.topRows<2>() = J_t_a;
    J_z_a(2, 2) = -1.0;
    J_z_b.topLeftCorner<2, 2>() = J_t_b;
    J_z_b(2, 2) = 1.0;
    if (J) *J = {J_z_a, J_z_b};
    return Eigen::Vector3d(t.x(), t.y(), WrapAngle(b.theta() - a.theta()));
  }
};

// A scalar block (a 1-D kind, e.g. a sensor bias) measured directly.
class ScalarFixModel final : public TestModel {
 public:
  int MeasurementDim() const override { return 1; }
  Eigen::VectorXd Eval(const Means& means, Jacobians* J) const override {
    if (J) *J = {Eigen::Matrix<double, 1, 1>::Identity()};
    return means[0];
  }
};

// A line in the world frame, (ρ, α): the points p with pᵀ(cos α, sin α) = ρ. Seen from pose
// (x, y, θ) it is (ρ − x cos α − y sin α, α − θ). α is an angle, wrapped by the filter.
class LineModel final : public TestModel {
 public:
  explicit LineModel(int line_kind) : line_kind_(line_kind) {}
  int MeasurementDim() const override { return 2; }
  std::vector<int> AngleRows() const override { return {1}; }
  int NewBlockKind() const override { return line_kind_; }

  Eigen::VectorXd Eval(const Means& means, Jacobians* J) const override {
    const Eigen::Vector3d& x = means[0];
    const double rho = means[1][0], alpha = means[1][1];
    const double c = std::cos(alpha), s = std::sin(alpha);
    Eigen::Matrix<double, 2, 3> J_z_x;
    J_z_x << -c, -s, 0, 0, 0, -1;
    Eigen::Matrix2d J_z_l;
    J_z_l << 1, x[0] * s - x[1] * c, 0, 1;
    if (J) *J = {J_z_x, J_z_l};
    return Eigen::Vector2d(rho - x[0] * c - x[1] * s, WrapAngle(alpha - x[2]));
  }
  // The inverse: α = α_z + θ, ρ = ρ_z + x cos α + y sin α.
  static Eigen::Vector2d InvertLine(const Eigen::Vector3d& x, const Eigen::Vector2d& z,
                                    Eigen::Matrix<double, 2, 3>* J_l_x, Eigen::Matrix2d* J_l_z) {
    const double alpha = WrapAngle(z[1] + x[2]);
    const double c = std::cos(alpha), s = std::sin(alpha);
    const double d_rho_d_alpha = -x[0] * s + x[1] * c;
    if (J_l_x) *J_l_x << c, s, d_rho_d_alpha, 0, 0, 1;
    if (J_l_z) *J_l_z << 1, d_rho_d_alpha, 0, 1;
    return {z[0] + x[0] * c + x[1] * s, alpha};
  }
  BlockInversion Invert(const BlockEkf& ekf, std::span<const int> observers,
                        const BlockVector& z) const override {
    Eigen::Matrix<double, 2, 3> J_l_x;
    Eigen::Matrix2d J_l_z;
    BlockInversion out;
    out.mean = InvertLine(ekf.Mean(observers[0]), z, &J_l_x, &J_l_z);
    out.J_new_blocks.Add(observers[0], J_l_x);
    out.J_new_z = J_l_z;
    return out;
  }

 private:
  int line_kind_;
};

// Range-bearing to a point, on dense means (the reference side of PointLandmarkModel).
Eigen::VectorXd RangeBearingEval(const Means& means, Jacobians* J) {
  Eigen::Matrix<double, 2, 3> J_z_x;
  Eigen::Matrix2d J_z_l;
  const RangeBearing rb = PredictRangeBearing(Pose2(means[0]), means[1], &J_z_x, &J_z_l);
  *J = {J_z_x, J_z_l};
  return Eigen::Vector2d(rb.range_m, rb.bearing_rad);
}

// ---- A BlockEkf and the dense reference driven through the same operations. ----

struct Mirror {
  BlockEkf ekf{16};  // small: the state grows (and flushes) while blocks are added
  DenseEkf ref;

  void AddBlock(int kind, const Eigen::VectorXd& mean, const Eigen::MatrixXd& cov) {
    ekf.AddBlock(kind, mean, cov);
    AppendAngles(kind);
    ref.Augment(mean, Eigen::MatrixXd::Zero(mean.size(), ref.x.size()),
                Eigen::MatrixXd::Identity(mean.size(), mean.size()), cov);
  }
  void AppendAngles(int kind) {
    for (const int a : ekf.kind(kind).angle_components) {
      ref.angles.push_back(static_cast<int>(ref.x.size()) + a);
    }
  }
  void PredictPose(int block, const OdometryModel& motion, const Control& u) {
    const int o = ekf.BlockOffset(block);
    Eigen::Matrix3d F;
    ControlJacobian G;
    const Pose2 moved = motion.Move(ekf.PoseOf(block), u, 0.1, &F, &G);
    const ControlCovariance Q = motion.Noise(u, 0.1);
    ekf.PredictPose(block, moved, F, G, Q);
    Eigen::MatrixXd F_full = Eigen::MatrixXd::Identity(ref.x.size(), ref.x.size());
    F_full.block<3, 3>(o, o) = F;
    ref.P = F_full * ref.P * F_full.transpose();
    ref.P.block<3, 3>(o, o) += G * Q * G.transpose();
    ref.x.segment<3>(o) = motion.Move(Pose2(ref.x.segment<3>(o)), u, 0.1).vector();
  }
  // One observation through the block filter (deferred) and the dense reference.
  void Observe(const ObservationModel& model,
               const std::function<Eigen::VectorXd(const Means&, Jacobians*)>& dense_eval,
               std::vector<int> blocks, const Eigen::VectorXd& z, const Eigen::MatrixXd& R) {
    ASSERT_TRUE(ekf.Update(Linearise(model, ekf, blocks, z, R)));
    Means means;
    for (const int b : blocks) means.push_back(ref.x.segment(ekf.BlockOffset(b), ekf.BlockDim(b)));
    Jacobians J;
    const Eigen::VectorXd z_pred = dense_eval(means, &J);
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(z.size(), ref.x.size());
    for (std::size_t i = 0; i < blocks.size(); ++i) {
      H.middleCols(ekf.BlockOffset(blocks[i]), ekf.BlockDim(blocks[i])) += J[i];
    }
    ref.Update(Eigen::VectorXd(model.Innovation(z, z_pred)), H, R);
  }
  // A new block from `observer`'s measurement z, on both sides.
  int Augment(const ObservationModel& model, int observer, const Eigen::Vector2d& z,
              const Eigen::Matrix2d& R,
              const std::function<Eigen::Vector2d(const Eigen::Vector3d&, const Eigen::Vector2d&,
                                                  Eigen::Matrix<double, 2, 3>*, Eigen::Matrix2d*)>&
                  dense_invert) {
    const int observers[] = {observer};
    const int block = AugmentFrom(model, ekf, observers, z, R);
    const int o = ekf.BlockOffset(observer);
    Eigen::Matrix<double, 2, 3> J_l_x;
    Eigen::Matrix2d J_l_z;
    const Eigen::Vector2d l = dense_invert(ref.x.segment<3>(o), z, &J_l_x, &J_l_z);
    AppendAngles(ekf.BlockKindOf(block));
    ref.Augment(l, ref.Spread(J_l_x, o), J_l_z, R);
    return block;
  }
  void ExpectEqual(const std::string& where) const {
    ASSERT_EQ(ekf.StateSize(), ref.x.size()) << where;
    EXPECT_LT(MaxAbsDiff(ekf.State(), ref.x), 1e-9) << where;
    EXPECT_LT(MaxAbsDiff(ekf.Covariance(), ref.P), 1e-9) << where;
  }
};

Eigen::Vector2d DenseInvertRangeBearing(const Eigen::Vector3d& x, const Eigen::Vector2d& z,
                                        Eigen::Matrix<double, 2, 3>* J_l_x,
                                        Eigen::Matrix2d* J_l_z) {
  return InvertRangeBearing(Pose2(x), {z[0], z[1]}, J_l_x, J_l_z);
}

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

// ---- Two pose blocks: vehicle-vehicle sightings, a position fix, shared landmarks. ----

TEST(BlockEkf, TwoPoseBlocksWithVehicleVehicleObservationEqualDenseEkf) {
  const RangeBearingModel sensor;
  Mirror m;
  const int point_kind = m.ekf.RegisterKind({2, {}, false});
  const PointLandmarkModel points(sensor, point_kind, 5.0);
  const RelativePositionModel relative;
  const PositionFixModel fix;
  const OdometryModel motion;
  const Eigen::Matrix2d R_rb = Eigen::Vector2d(0.05 * 0.05, 0.01 * 0.01).asDiagonal();
  const Eigen::Matrix2d R_xy = 0.04 * Eigen::Matrix2d::Identity();

  const int a = 0;
  m.AddBlock(kPoseKind, Eigen::Vector3d(0.0, 0.0, 0.3),
             Eigen::Vector3d(0.1, 0.1, 0.01).asDiagonal());
  Rng rng(31);
  std::vector<int> landmarks;
  for (int i = 0; i < 5; ++i) {
    landmarks.push_back(m.Augment(points, a, {rng.Uniform(3, 15), rng.Uniform(-2, 2)}, R_rb,
                                  DenseInvertRangeBearing));
  }
  m.PredictPose(a, motion, Odo(0.5, 0.1, 0.05));
  // Pose B after the landmarks: its cross-covariances lie in both the row and the column part.
  const int b = m.ekf.NumBlocks();
  m.AddBlock(kPoseKind, Eigen::Vector3d(5.0, 1.0, 2.9),
             Eigen::Vector3d(0.2, 0.3, 0.02).asDiagonal());
  for (int i = 0; i < 3; ++i) {
    landmarks.push_back(m.Augment(points, b, {rng.Uniform(3, 15), rng.Uniform(-2, 2)}, R_rb,
                                  DenseInvertRangeBearing));
  }
  m.PredictPose(a, motion, Odo(0.4, 0.0, 0.1));
  m.PredictPose(b, motion, Odo(0.3, -0.1, -0.2));
  m.ExpectEqual("after prediction");

  // One deferred step mixing every observation shape.
  auto sight = [&](int pose, int l, double dr, double db) {
    const RangeBearing rb = PredictRangeBearing(m.ekf.PoseOf(pose), m.ekf.Mean(l));
    m.Observe(points, RangeBearingEval, {pose, l},
              Eigen::Vector2d(rb.range_m + dr, rb.bearing_rad + db), R_rb);
  };
  auto eval = [](const TestModel& model) {
    return [&model](const Means& means, Jacobians* J) { return model.Eval(means, J); };
  };
  sight(a, landmarks[1], 0.1, 0.01);
  sight(b, landmarks[6], -0.1, 0.02);
  const Eigen::Vector2d a_sees_b = m.ekf.PoseOf(a).TransformTo(m.ekf.PoseOf(b).translation());
  m.Observe(relative, eval(relative), {a, b}, a_sees_b + Eigen::Vector2d(0.3, -0.2), R_xy);
  m.ExpectEqual("after the vehicle-vehicle sighting");
  sight(b, landmarks[0], 0.05, -0.01);  // B sees a landmark A mapped
  const int added = m.Augment(points, b, {6.0, 0.4}, R_rb, DenseInvertRangeBearing);
  sight(a, added, 0.2, 0.0);
  m.Observe(fix, eval(fix), {b}, m.ekf.Mean(b).head<2>() + Eigen::Vector2d(0.2, 0.1), R_xy);
  m.Observe(relative, eval(relative), {b, a},
            m.ekf.PoseOf(b).TransformTo(m.ekf.PoseOf(a).translation()) + Eigen::Vector2d(-0.1, 0.1),
            R_xy);
  EXPECT_TRUE(m.ekf.HasPendingDowndate());
  m.ExpectEqual("in the step");
  m.ekf.ApplyPendingDowndate();
  m.ExpectEqual("after the step");
}

// Measurements other than 2-D and blocks other than 2-D or 3-D take BlockEkf's dynamic-size
// path (internal::WithDim): the same results as the dense filter.
TEST(BlockEkf, OneAndThreeDimensionalMeasurementsAndAScalarBlockEqualDenseEkf) {
  const RangeBearingModel sensor;
  Mirror m;
  const int point_kind = m.ekf.RegisterKind({2, {}, false});
  const int scalar_kind = m.ekf.RegisterKind({1, {}, false});
  const PointLandmarkModel points(sensor, point_kind, 5.0);
  const RangeOnlyModel range;
  const RelativePoseModel relative;
  const ScalarFixModel scalar;
  const OdometryModel motion;
  const Eigen::Matrix2d R_rb = Eigen::Vector2d(0.05 * 0.05, 0.01 * 0.01).asDiagonal();
  auto eval = [](const TestModel& model) {
    return [&model](const Means& means, Jacobians* J) { return model.Eval(means, J); };
  };
  m.AddBlock(kPoseKind, Eigen::Vector3d(0.0, 0.0, 0.3), Eigen::Vector3d(0.1, 0.1, 0.01).asDiagonal());
  const int l = m.Augment(points, 0, {5.0, 0.2}, R_rb, DenseInvertRangeBearing);
  const int b = m.ekf.NumBlocks();
  m.AddBlock(kPoseKind, Eigen::Vector3d(4.0, 1.0, 2.0), Eigen::Vector3d(0.2, 0.3, 0.02).asDiagonal());
  const int bias = m.ekf.NumBlocks();
  m.AddBlock(scalar_kind, Eigen::Matrix<double, 1, 1>(0.5), Eigen::Matrix<double, 1, 1>(0.09));
  m.PredictPose(0, motion, Odo(0.4, 0.0, 0.1));
  m.Observe(range, eval(range), {0, l}, Eigen::Matrix<double, 1, 1>(5.3),
            Eigen::Matrix<double, 1, 1>(0.01));
  const Eigen::VectorXd rel = relative.Eval({m.ekf.Mean(0), m.ekf.Mean(b)}, nullptr);
  m.Observe(relative, eval(relative), {0, b}, rel + Eigen::Vector3d(0.2, -0.1, 0.05),
            Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  m.Observe(scalar, eval(scalar), {bias}, Eigen::Matrix<double, 1, 1>(0.35),
            Eigen::Matrix<double, 1, 1>(0.04));
  m.ExpectEqual("in the step");
  EXPECT_NEAR(m.ekf.MahalanobisSquared(Linearise(scalar, m.ekf, std::vector<int>{bias},
                                                 Eigen::Matrix<double, 1, 1>(0.35),
                                                 Eigen::Matrix<double, 1, 1>(0.04))),
              std::pow(0.35 - m.ekf.Mean(bias)[0], 2) /
                  (m.ekf.CovarianceBlock(bias, bias)(0, 0) + 0.04),
              1e-12);
  m.ekf.ApplyPendingDowndate();
  m.ExpectEqual("after the step");
}

// ---- A (ρ, α) line landmark kind whose α crosses ±π. ----

TEST(BlockEkf, LineLandmarkKindWithWrappedAngleEqualsDenseEkf) {
  const RangeBearingModel sensor;
  Mirror m;
  const int point_kind = m.ekf.RegisterKind({2, {}, false});
  const int line_kind = m.ekf.RegisterKind({2, {1}, false});
  const PointLandmarkModel points(sensor, point_kind, 5.0);
  const LineModel lines(line_kind);
  const OdometryModel motion;
  const Eigen::Matrix2d R_rb = Eigen::Vector2d(0.05 * 0.05, 0.01 * 0.01).asDiagonal();
  const Eigen::Matrix2d R_line = Eigen::Vector2d(0.05 * 0.05, 0.05 * 0.05).asDiagonal();
  const Eigen::Matrix2d R_line_fine = Eigen::Vector2d(0.02 * 0.02, 0.01 * 0.01).asDiagonal();
  auto line_eval = [&](const Means& means, Jacobians* J) { return lines.Eval(means, J); };

  m.AddBlock(kPoseKind, Eigen::Vector3d(1.0, 2.0, 0.3),
             Eigen::Vector3d(0.05, 0.05, 0.01).asDiagonal());
  const int p0 = m.Augment(points, 0, {5.0, 0.5}, R_rb, DenseInvertRangeBearing);
  // World α = π − 0.05: seen from θ = 0.3 at α_z = π − 0.35.
  const int wall = m.Augment(lines, 0, {4.0, kPi - 0.35}, R_line, LineModel::InvertLine);
  const int other = m.Augment(lines, 0, {3.0, -1.2}, R_line, LineModel::InvertLine);
  m.PredictPose(0, motion, Odo(0.3, 0.0, 0.02));
  m.ExpectEqual("after augmentation");
  const double alpha_before = m.ekf.Mean(wall)[1];
  ASSERT_GT(alpha_before, 3.0);

  // A sighting of the wall whose α lies 0.1 rad further on, across π.
  Eigen::Vector2d z = lines.Eval({m.ekf.Mean(0), m.ekf.Mean(wall)}, nullptr);
  z[1] = WrapAngle(z[1] + 0.1);
  m.Observe(lines, line_eval, {0, wall}, z, R_line_fine);
  const double alpha_after = m.ekf.Mean(wall)[1];
  EXPECT_LT(alpha_after, -3.0) << "α should have crossed π and been wrapped";
  EXPECT_GE(alpha_after, -kPi);
  m.ExpectEqual("after the crossing update");

  Eigen::Vector2d z_other = lines.Eval({m.ekf.Mean(0), m.ekf.Mean(other)}, nullptr);
  z_other += Eigen::Vector2d(0.05, -0.02);
  m.Observe(lines, line_eval, {0, other}, z_other, R_line_fine);
  const RangeBearing rb = PredictRangeBearing(m.ekf.PoseOf(0), m.ekf.Mean(p0));
  m.Observe(points, RangeBearingEval, {0, p0}, Eigen::Vector2d(rb.range_m - 0.05, rb.bearing_rad),
            R_rb);
  m.ekf.ApplyPendingDowndate();
  m.ExpectEqual("after the step");
}

// ---- The test models' Jacobians. ----

TEST(TestModels, JacobiansMatchCentralDifferences) {
  Rng rng(41);
  const LineModel lines(1);
  const RelativePositionModel relative;
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Vector3d x = testing::RandomPose(rng).vector();
    const Eigen::Vector3d y = testing::RandomPose(rng).vector();
    const Eigen::Vector2d l = testing::UniformVector2(rng, -5, 5, -3.1, 3.1);
    Jacobians J;
    lines.Eval({x, l}, &J);
    const auto h_x = [&](const Eigen::VectorXd& v) { return lines.Eval({v, l}, nullptr); };
    const auto h_l = [&](const Eigen::VectorXd& v) { return lines.Eval({x, v}, nullptr); };
    EXPECT_LT(MaxAbsDiff(J[0], testing::NumericJacobian(h_x, x, 1)), 1e-6);
    EXPECT_LT(MaxAbsDiff(J[1], testing::NumericJacobian(h_l, l, 1)), 1e-6);

    const Eigen::Vector2d z = testing::UniformVector2(rng, -5, 5, -3.1, 3.1);
    Eigen::Matrix<double, 2, 3> J_l_x;
    Eigen::Matrix2d J_l_z;
    LineModel::InvertLine(x, z, &J_l_x, &J_l_z);
    const auto g_x = [&](const Eigen::VectorXd& v) {
      return Eigen::VectorXd(LineModel::InvertLine(v, z, nullptr, nullptr));
    };
    const auto g_z = [&](const Eigen::VectorXd& v) {
      return Eigen::VectorXd(LineModel::InvertLine(x, v, nullptr, nullptr));
    };
    EXPECT_LT(MaxAbsDiff(J_l_x, testing::NumericJacobian(g_x, x, 1)), 1e-6);
    EXPECT_LT(MaxAbsDiff(J_l_z, testing::NumericJacobian(g_z, z, 1)), 1e-6);

    relative.Eval({x, y}, &J);
    const auto r_a = [&](const Eigen::VectorXd& v) { return relative.Eval({v, y}, nullptr); };
    const auto r_b = [&](const Eigen::VectorXd& v) { return relative.Eval({x, v}, nullptr); };
    EXPECT_LT(MaxAbsDiff(J[0], testing::NumericJacobian(r_a, x)), 1e-6);
    EXPECT_LT(MaxAbsDiff(J[1], testing::NumericJacobian(r_b, y)), 1e-6);
  }
}

}  // namespace
}  // namespace slamkit

namespace slamkit {
namespace {

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
