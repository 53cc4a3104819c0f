// Test-only block kinds and observation models, each defined by its math on the means of its
// blocks, and Mirror: a BlockEkf and the dense textbook EKF driven through the same operations
// (block_ekf_test.cpp, block_ekf_kinds_test.cpp).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <functional>
#include <span>
#include <vector>

#include "filters/dense_reference.hpp"
#include "slamkit/core/angle.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf/observation_model.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit::block_ekf_kinds {

using testing::DenseEkf;
using testing::MaxAbsDiff;
using Means = std::vector<Eigen::VectorXd>;
using Jacobians = std::vector<Eigen::MatrixXd>;

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
inline Eigen::VectorXd RangeBearingEval(const Means& means, Jacobians* J) {
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

inline Eigen::Vector2d DenseInvertRangeBearing(const Eigen::Vector3d& x, const Eigen::Vector2d& z,
                                        Eigen::Matrix<double, 2, 3>* J_l_x,
                                        Eigen::Matrix2d* J_l_z) {
  return InvertRangeBearing(Pose2(x), {z[0], z[1]}, J_l_x, J_l_z);
}

}  // namespace slamkit::block_ekf_kinds
