// The line landmark kind (SPEC S1): its observation model through the BlockEkf interface, the
// normalisation of a line's state, and the association of lines (overlap) and corners (kind).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <numbers>

#include "common/numeric_jacobian.hpp"
#include "filters/dense_reference.hpp"
#include "slamkit/filters/features/feature_ekf_slam.hpp"
#include "slamkit/filters/features/line_landmark_model.hpp"
#include "slamkit/models/odometry.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

using testing::MaxAbsDiff;
constexpr double kLinePi = std::numbers::pi;

// A BlockEkf holding pose `x` and line `l` (blocks 0 and 1), for the model to read.
struct PoseAndLine {
  BlockEkf ekf;
  int line_kind;
  PoseAndLine(const Eigen::Vector3d& x, const Eigen::Vector2d& l)
      : line_kind(ekf.RegisterKind(LineBlockKind())) {
    ekf.AddBlock(kPoseKind, x, Eigen::Matrix3d::Identity());
    ekf.AddBlock(line_kind, l, Eigen::Matrix2d::Identity());
  }
};

Eigen::VectorXd PredictAt(const Eigen::Vector3d& x, const Eigen::Vector2d& l) {
  PoseAndLine s(x, l);
  const LineLandmarkModel model(s.line_kind, 0.0);
  const int blocks[] = {0, 1};
  return Eigen::Vector2d(model.Predict(s.ekf, blocks).z);
}

// Predict's and Invert's Jacobians against central differences of the model itself, at random
// poses and lines, on both sides of the line (ρ flips), with α near ±π; lines within 0.3 m of the
// robot (or of the world origin, for Invert) are left out: the flip makes ρ non-differentiable
// at 0, and the gate keeps those out of the filter.
TEST(LineLandmarkModel, PredictJacobiansMatchCentralDifferencesThroughTheBlockEkf) {
  Rng rng(11);
  int flipped = 0, tested = 0;
  while (tested < 200) {
    const Eigen::Vector3d x = testing::RandomPose(rng, 5.0).vector();
    Eigen::Vector2d l = testing::UniformVector2(rng, 0.3, 6.0, -kLinePi, kLinePi);
    if (tested % 4 == 0) l[1] = WrapLineAngle(kLinePi - rng.Uniform(-0.01, 0.01));
    const double rho_robot = l[0] - x[0] * std::cos(l[1]) - x[1] * std::sin(l[1]);
    if (std::abs(rho_robot) < 0.3) continue;
    ++tested;
    if (rho_robot < 0.0) ++flipped;
    PoseAndLine s(x, l);
    const LineLandmarkModel model(s.line_kind, 0.0);
    const int blocks[] = {0, 1};
    const BlockPrediction p = model.Predict(s.ekf, blocks);
    ASSERT_EQ(p.J_z_blocks.size, 2);
    EXPECT_GE(p.z[0], 0.0);
    const auto h_x = [&](const Eigen::VectorXd& v) { return PredictAt(v, l); };
    const auto h_l = [&](const Eigen::VectorXd& v) { return PredictAt(x, v); };
    EXPECT_LT(MaxAbsDiff(p.J_z_blocks.items[0].J, testing::NumericJacobian(h_x, x, 1)), 1e-6);
    EXPECT_LT(MaxAbsDiff(p.J_z_blocks.items[1].J, testing::NumericJacobian(h_l, l, 1)), 1e-6);

    // Invert: the world line that appears as z, and its Jacobians.
    const BlockVector z = p.z;
    const BlockInversion inv = model.Invert(s.ekf, std::span<const int>(blocks, 1), z);
    EXPECT_LT(std::abs(inv.mean[0] - l[0]) + std::abs(WrapAngle(inv.mean[1] - l[1])), 1e-9);
    const auto g_z = [&](const Eigen::VectorXd& v) {
      return Eigen::VectorXd(model.Invert(s.ekf, std::span<const int>(blocks, 1), v).mean);
    };
    EXPECT_LT(MaxAbsDiff(inv.J_new_z, testing::NumericJacobian(g_z, Eigen::VectorXd(z), 1)), 1e-6);
    const auto g_x = [&](const Eigen::VectorXd& v) {
      const PoseAndLine moved(v, l);
      return Eigen::VectorXd(model.Invert(moved.ekf, std::span<const int>(blocks, 1), z).mean);
    };
    ASSERT_EQ(inv.J_new_blocks.size, 1);
    EXPECT_LT(MaxAbsDiff(inv.J_new_blocks.items[0].J, testing::NumericJacobian(g_x, x, 1)), 1e-6);
  }
  EXPECT_GT(flipped, 20) << "the far side of the lines should be covered";
}

TEST(LineLandmarkModel, InnovationWrapsAlphaAndGateRejectsLinesThroughTheRobot) {
  PoseAndLine s(Eigen::Vector3d(1.0, 0.0, 0.0), Eigen::Vector2d(1.1, 0.0));
  const LineLandmarkModel model(s.line_kind, 0.3);
  const int blocks[] = {0, 1};
  EXPECT_FALSE(model.Gate(s.ekf, blocks)) << "predicted ρ = 0.1 m < 0.3 m";
  PoseAndLine far(Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector2d(1.1, 0.0));
  EXPECT_TRUE(model.Gate(far.ekf, blocks));
  const BlockVector nu =
      model.Innovation(LineVector({2.0, kLinePi - 0.01}), LineVector({2.1, -kLinePi + 0.01}));
  EXPECT_NEAR(nu[0], -0.1, 1e-12);
  EXPECT_NEAR(nu[1], -0.02, 1e-12);
}

// An update that pushes a world line's ρ below zero leaves (−ρ, α + π) and the covariance of that
// change of coordinates: the dense EKF's posterior with ρ's row and column negated.
TEST(LineLandmarkModel, UpdateThatMakesRhoNegativeIsNormalised) {
  BlockEkf ekf;
  const int line_kind = ekf.RegisterKind(LineBlockKind());
  const LineLandmarkModel model(line_kind, 0.0);
  ekf.AddBlock(kPoseKind, Eigen::Vector3d(0.0, 0.0, 0.0),
               Eigen::Vector3d(0.04, 0.04, 0.01).asDiagonal());
  const int observers[] = {0};
  const int line = AugmentFrom(model, ekf, observers, LineVector({0.1, 0.5}),
                               Eigen::Vector2d(0.09, 0.001).asDiagonal());
  const Eigen::VectorXd x0 = ekf.State();
  const Eigen::MatrixXd P0 = ekf.Covariance();
  ASSERT_GT(std::abs(P0(3, 0)), 1e-4) << "the line should be correlated with the pose";

  // A direct fix of the line's (ρ, α): H = [0 I], ν = (−0.4, 0).
  Linearisation fix;
  fix.innovation = Eigen::Vector2d(-0.4, 0.0);
  BlockMatrix I2 = BlockMatrix::Identity(2, 2);
  fix.H.Add(line, I2);
  fix.R = Eigen::Vector2d(1e-4, 1e-4).asDiagonal();
  ASSERT_TRUE(ekf.Update(fix));
  ekf.ApplyPendingDowndate();

  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(2, 5);
  H.rightCols(2).setIdentity();
  const Eigen::MatrixXd S = H * P0 * H.transpose() + Eigen::MatrixXd(fix.R);
  const Eigen::MatrixXd K = P0 * H.transpose() * S.inverse();
  Eigen::VectorXd x1 = x0 + K * Eigen::VectorXd(fix.innovation);
  Eigen::MatrixXd P1 = P0 - K * S * K.transpose();
  ASSERT_LT(x1[3], -0.2) << "the update itself must push ρ below zero";
  const Eigen::Matrix<double, 5, 1> t(1, 1, 1, -1, 1);
  x1[3] = -x1[3];
  x1[4] = WrapLineAngle(x1[4] + kLinePi);
  P1 = t.asDiagonal() * P1 * t.asDiagonal();

  EXPECT_GE(ekf.Mean(line)[0], 0.0);
  EXPECT_LT(MaxAbsDiff(ekf.State(), x1), 1e-12);
  EXPECT_LT(MaxAbsDiff(ekf.Covariance(), P1), 1e-12);
}

// ---- Association through FeatureEkfSlam. ----

LineSegment Wall(double rho, double alpha, double from_m, double to_m) {
  LineSegment s;
  s.line = {rho, alpha};
  s.covariance = Eigen::Vector2d(1e-4, 1e-5).asDiagonal();
  const Eigen::Vector2d n(std::cos(alpha), std::sin(alpha)), t(-n.y(), n.x());
  s.start_m = rho * n + from_m * t;
  s.end_m = rho * n + to_m * t;
  s.num_points = 20;
  return s;
}

FeatureEkfSlam MakeSlam() {
  return FeatureEkfSlam(FeatureEkfSlamParams{}, std::make_unique<OdometryModel>());
}

// Two walls on the line y = 2, 5 m apart along it: the same (ρ, α), so only the overlap test
// tells them apart.
TEST(FeatureEkfSlam, TwoCollinearWallsFiveMetresApartAreTwoLandmarks) {
  FeatureEkfSlam slam = MakeSlam();
  ScanFeatures scan;
  scan.lines = {Wall(2.0, kLinePi / 2, -7.5, -2.5), Wall(2.0, kLinePi / 2, 2.5, 7.5)};
  FeatureDecisions d = slam.Update(scan);
  EXPECT_EQ(slam.NumLines(), 2);
  EXPECT_EQ(slam.NumActiveLines(), 2);
  // Seen again, each matches its own landmark.
  d = slam.Update(scan);
  ASSERT_EQ(d.lines.size(), 2u);
  EXPECT_EQ(d.lines[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d.lines[0].landmark, 0);
  EXPECT_EQ(d.lines[1].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(d.lines[1].landmark, 1);
  EXPECT_EQ(slam.NumLines(), 2);
  // A sighting that continues the first wall (x in [2.5, 7.5]) within the margin extends it.
  ScanFeatures more;
  more.lines = {Wall(2.0, kLinePi / 2, -2.8, -2.2)};  // x in [2.2, 2.8]
  d = slam.Update(more);
  EXPECT_EQ(d.lines[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(slam.NumLines(), 2);
  const LineExtent& e = slam.LineExtentOf(0);
  EXPECT_NEAR(std::min(e.start_m.x(), e.end_m.x()), 2.2, 0.05);
  EXPECT_NEAR(std::max(e.start_m.x(), e.end_m.x()), 7.5, 0.05);
}

// Two glimpses of one wall 1 m apart (beyond the overlap margin) start two landmarks; a sighting
// that spans both matches one, whose extent then meets the other's: the two are fused into one.
TEST(FeatureEkfSlam, LandmarksOfOneWallAreFusedWhenTheirExtentsMeet) {
  FeatureEkfSlam slam = MakeSlam();
  ScanFeatures glimpses;
  glimpses.lines = {Wall(2.0, kLinePi / 2, -3.0, -0.5), Wall(2.02, kLinePi / 2 + 0.005, 0.5, 3.0)};
  slam.Update(glimpses);
  ASSERT_EQ(slam.NumActiveLines(), 2);
  ScanFeatures whole;
  whole.lines = {Wall(2.01, kLinePi / 2, -2.0, 2.0)};
  const FeatureDecisions d = slam.Update(whole);
  EXPECT_EQ(d.lines[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(slam.NumActiveLines(), 1);
  EXPECT_EQ(slam.LineMergedInto(1), 0);
  EXPECT_NEAR(slam.Line(0).rho_m, slam.Line(1).rho_m, 1e-3);
  EXPECT_NEAR(slam.Line(0).alpha_rad, slam.Line(1).alpha_rad, 1e-3);
  const LineExtent& e = slam.LineExtentOf(0);
  EXPECT_NEAR(std::abs(e.end_m.x() - e.start_m.x()), 6.0, 0.05);
  // The merged landmark is no candidate any more: the next sighting matches landmark 0.
  EXPECT_EQ(slam.Update(whole).lines[0].landmark, 0);
}

// Two parallel walls 0.6 m apart, seen so uncertainly that their difference passes the χ² gate:
// they are two walls by their geometry (beyond the new-landmark separation), so they are never
// fused, which would pull both, and the pose, onto one line.
TEST(FeatureEkfSlam, UncertainParallelWallsAreNotFused) {
  FeatureEkfSlam slam = MakeSlam();
  auto uncertain = [](LineSegment s) {
    s.covariance = Eigen::Vector2d(0.25, 1e-3).asDiagonal();
    return s;
  };
  ScanFeatures both;
  both.lines = {uncertain(Wall(2.0, kLinePi / 2, -3.0, 3.0)), uncertain(Wall(2.6, kLinePi / 2, -2.0, 2.0))};
  slam.Update(both);
  ASSERT_EQ(slam.NumActiveLines(), 2);
  ScanFeatures near_one;
  near_one.lines = {uncertain(Wall(2.0, kLinePi / 2, -3.0, 3.0))};
  const FeatureDecisions d = slam.Update(near_one);
  ASSERT_EQ(d.lines[0].kind, AssociationDecision::Kind::kMatched);
  EXPECT_EQ(slam.NumActiveLines(), 2);
  EXPECT_NEAR(std::abs(slam.Line(1).rho_m - slam.Line(0).rho_m), 0.6, 0.05);
}

TEST(FeatureEkfSlam, ShortSightingsStartNoLandmark) {
  FeatureEkfSlam slam = MakeSlam();
  ScanFeatures scan;
  scan.lines = {Wall(2.0, kLinePi / 2, 0.0, 0.5)};
  const FeatureDecisions d = slam.Update(scan);
  EXPECT_EQ(d.lines[0].kind, AssociationDecision::Kind::kDropped);
  EXPECT_EQ(slam.NumLines(), 0);
}

Corner MakeCorner(double x, double y, CornerKind kind) {
  Corner c;
  c.point_m = Eigen::Vector2d(x, y);
  c.covariance = Eigen::Vector2d(1e-4, 1e-4).asDiagonal();
  c.kind = kind;
  return c;
}

TEST(FeatureEkfSlam, ConcaveCornerNeverMatchesAConvexOne) {
  FeatureEkfSlam slam = MakeSlam();
  ScanFeatures scan;
  scan.corners = {MakeCorner(3.0, 1.0, CornerKind::kConcave)};
  slam.Update(scan);
  ASSERT_EQ(slam.NumCorners(), 1);
  FeatureDecisions d = slam.Update(scan);
  EXPECT_EQ(d.corners[0].kind, AssociationDecision::Kind::kMatched);
  scan.corners = {MakeCorner(3.0, 1.0, CornerKind::kConvex)};
  d = slam.Update(scan);
  EXPECT_EQ(d.corners[0].kind, AssociationDecision::Kind::kNew);
  EXPECT_EQ(slam.NumCorners(), 2);
  EXPECT_EQ(slam.CornerKindOf(1), CornerKind::kConvex);
}

}  // namespace
}  // namespace slamkit
