// The block-structured EKF against the dense textbook sequential EKF on kinds defined for the
// test only (block_ekf_kinds.hpp): a second pose with vehicle-vehicle and position-fix
// observations, one- and three-dimensional measurements, a scalar block and a (ρ, α) line
// landmark. None of them needs a change to the update code.

#include "slamkit/filters/ekf/block_ekf.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <numbers>

#include "block_ekf_kinds.hpp"
#include "common/numeric_jacobian.hpp"
#include "common/ordered_draws.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

using block_ekf_kinds::DenseEkf;
using block_ekf_kinds::Jacobians;
using block_ekf_kinds::MaxAbsDiff;
using block_ekf_kinds::Means;
using block_ekf_kinds::DenseInvertRangeBearing;
using block_ekf_kinds::LineModel;
using block_ekf_kinds::Mirror;
using block_ekf_kinds::PositionFixModel;
using block_ekf_kinds::RangeOnlyModel;
using block_ekf_kinds::RelativePoseModel;
using block_ekf_kinds::RelativePositionModel;
using block_ekf_kinds::ScalarFixModel;
using block_ekf_kinds::TestModel;

constexpr double kPi = std::numbers::pi;

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
