#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "common/numeric_jacobian.hpp"
#include "features/polygon_room.hpp"
#include "slamkit/features/corners.hpp"
#include "slamkit/features/scan_features.hpp"

namespace slamkit {
namespace {

using testing::MakePolygonRoom;
using testing::NumericJacobian;
using testing::ScanPolygonRoom;

TEST(IntersectLines, PointLiesOnBothLinesAndJacobianMatchesCentralDifferences) {
  Rng rng(2);
  for (int i = 0; i < 100; ++i) {
    const PolarLine a{rng.Uniform(0.1, 8.0), rng.Uniform(-3.1, 3.1)};
    const PolarLine b{rng.Uniform(0.1, 8.0), WrapLineAngle(a.alpha_rad + rng.Uniform(0.3, 2.8))};
    Eigen::Matrix<double, 2, 4> J;
    const Eigen::Vector2d p = IntersectLines(a, b, &J);
    EXPECT_NEAR(DistanceToLine(a, p), 0.0, 1e-9);
    EXPECT_NEAR(DistanceToLine(b, p), 0.0, 1e-9);
    auto f = [](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return IntersectLines({v[0], v[1]}, {v[2], v[3]});
    };
    const Eigen::Vector4d v(a.rho_m, a.alpha_rad, b.rho_m, b.alpha_rad);
    EXPECT_TRUE(J.isApprox(NumericJacobian(f, v), 1e-6)) << J << "\n" << NumericJacobian(f, v);
  }
}

TEST(ExtractCorners, AngleRangeAndEndpointDistanceGateCorners) {
  const auto room = MakePolygonRoom(0.0);
  const std::vector<LineSegment> lines = ExtractLines(ScanPolygonRoom(room), {});
  ASSERT_EQ(lines.size(), 6u);
  LineExtractionParams p;
  EXPECT_EQ(ExtractCorners(lines, p).size(), 3u);
  p.min_corner_angle_rad = std::numbers::pi / 2.0 + 0.01;  // every corner here is 90°
  EXPECT_TRUE(ExtractCorners(lines, p).empty());
  p = {};
  p.max_corner_angle_rad = std::numbers::pi / 2.0 - 0.01;
  EXPECT_TRUE(ExtractCorners(lines, p).empty());
  // A generous end-point distance lets the pillar face x = 1 and the wall y = 4 behind it form
  // the false corner (1, 4); the default keeps it out.
  p = {};
  p.max_corner_endpoint_distance_m = 1.0;
  const std::vector<Corner> loose = ExtractCorners(lines, p);
  ASSERT_EQ(loose.size(), 4u);
  EXPECT_TRUE(loose[3].point_m.isApprox(Eigen::Vector2d(1.0, 4.0), 1e-4));
  EXPECT_EQ(loose[3].first_line, 4);
  EXPECT_EQ(loose[3].second_line, 5);
}

// Corner points within their stated covariance over many noisy scans (mean NEES of 2 dof is 2).
TEST(ExtractCorners, CornersAreConsistentWithTheirCovarianceOverManyScans) {
  const auto room = MakePolygonRoom(-2.0);
  LineExtractionParams params;
  params.sigma_range_m = 0.01;
  params.sigma_bearing_rad = 0.002;
  const Eigen::Vector2d truth[3] = {room.concave_corners[0], room.concave_corners[1],
                                    room.convex_corners[0]};
  Rng rng(8);
  constexpr int kRuns = 2000;
  double nees[3] = {0.0, 0.0, 0.0};
  int good = 0;
  for (int k = 0; k < kRuns; ++k) {
    const ScanFeatures f = ExtractFeatures(ScanPolygonRoom(room, &rng, 0.01, 0.002), params);
    if (f.corners.size() != 3u) continue;  // counted below, as in the line test
    ++good;
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(f.corners[i].kind, i < 2 ? CornerKind::kConcave : CornerKind::kConvex);
      const Eigen::Vector2d e = f.corners[i].point_m - truth[i];
      nees[i] += e.dot(f.corners[i].covariance.inverse() * e);
    }
  }
  EXPECT_GE(good, 0.99 * kRuns);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(nees[i] / good, 2.0, 0.3) << "corner " << i;
}

TEST(CornerRangeBearing, IsTheCornerInPolarFormWithItsCovarianceCarriedOver) {
  Corner c;
  c.point_m = {3.0, 4.0};
  c.covariance << 0.04, 0.0, 0.0, 0.01;
  Eigen::Matrix2d R;
  const RangeBearing z = CornerRangeBearing(c, &R);
  EXPECT_NEAR(z.range_m, 5.0, 1e-12);
  EXPECT_NEAR(z.bearing_rad, std::atan2(4.0, 3.0), 1e-12);
  // Range is along (0.6, 0.8): var = 0.36·0.04 + 0.64·0.01; bearing across, scaled by 1/r.
  EXPECT_NEAR(R(0, 0), 0.36 * 0.04 + 0.64 * 0.01, 1e-12);
  EXPECT_NEAR(R(1, 1), (0.64 * 0.04 + 0.36 * 0.01) / 25.0, 1e-12);
  // Back through the point model: the same corner.
  EXPECT_TRUE(InvertRangeBearing(Pose2(), z).isApprox(c.point_m, 1e-12));
}

// A laser mounted off the robot's centre: lines and corners come out where the room's walls and
// corners are in the robot frame, and the covariances follow the frame change.
TEST(ToRobotFrame, MovesLinesCornersAndCovariancesByTheLaserOffset) {
  const auto room = MakePolygonRoom(0.4);
  const Pose2 offset(0.25, -0.1, 0.3);
  Rng rng(1);
  const ScanFeatures sensor = ExtractFeatures(ScanPolygonRoom(room, &rng, 0.005, 0.0));
  const ScanFeatures robot = ToRobotFrame(sensor, offset);
  ASSERT_EQ(robot.lines.size(), room.visible_lines.size());
  ASSERT_EQ(robot.corners.size(), 3u);
  for (std::size_t i = 0; i < robot.lines.size(); ++i) {
    const PolarLine want = InvertLine(offset, room.visible_lines[i]);
    const Eigen::Vector2d e = LineInnovation(robot.lines[i].line, want);
    EXPECT_LT(e.dot(robot.lines[i].covariance.inverse() * e), 13.8) << "line " << i;
    EXPECT_NEAR(DistanceToLine(robot.lines[i].line, robot.lines[i].start_m), 0.0, 1e-9);
    auto by_z = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      const PolarLine l = InvertLine(offset, {v[0], v[1]});
      return Eigen::Vector2d(l.rho_m, l.alpha_rad);
    };
    const PolarLine z = sensor.lines[i].line;
    const Eigen::MatrixXd J = NumericJacobian(by_z, Eigen::Vector2d(z.rho_m, z.alpha_rad), 1);
    EXPECT_TRUE(robot.lines[i].covariance.isApprox(
        J * sensor.lines[i].covariance * J.transpose(), 1e-6));
  }
  EXPECT_TRUE(robot.corners[0].point_m.isApprox(offset.TransformFrom(room.concave_corners[0]),
                                                0.02));
  EXPECT_NEAR(robot.corners[2].covariance.trace(), sensor.corners[2].covariance.trace(), 1e-15);
}

}  // namespace
}  // namespace slamkit
