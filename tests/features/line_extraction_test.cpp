#include <cmath>
#include <limits>
#include <numbers>

#include <gtest/gtest.h>

#include "features/polygon_room.hpp"
#include "slamkit/features/line_extraction.hpp"
#include "slamkit/features/scan_features.hpp"

namespace slamkit {
namespace {

using testing::MakePolygonRoom;
using testing::PolygonRoom;
using testing::ScanPolygonRoom;

void ExpectLine(const PolarLine& got, const PolarLine& want, double tol_m, double tol_rad) {
  EXPECT_NEAR(got.rho_m, want.rho_m, tol_m);
  EXPECT_NEAR(WrapAngle(got.alpha_rad - want.alpha_rad), 0.0, tol_rad)
      << "alpha " << got.alpha_rad << " want " << want.alpha_rad;
  EXPECT_GE(got.rho_m, 0.0);
  EXPECT_GT(got.alpha_rad, -std::numbers::pi);
  EXPECT_LE(got.alpha_rad, std::numbers::pi);
}

class RoomAtAngle : public ::testing::TestWithParam<double> {};

// The room turned so that lines come out at α near 0, ±π/2 and ±π.
TEST_P(RoomAtAngle, NoiseFreeScanGivesTheVisibleWallsAndCorners) {
  const PolygonRoom room = MakePolygonRoom(GetParam());
  const ScanFeatures f = ExtractFeatures(ScanPolygonRoom(room), LineExtractionParams{});
  ASSERT_EQ(f.lines.size(), room.visible_lines.size());
  for (std::size_t i = 0; i < f.lines.size(); ++i) {
    SCOPED_TRACE(i);
    ExpectLine(f.lines[i].line, room.visible_lines[i], 1e-4, 1e-4);
    EXPECT_LT(f.lines[i].residual_rms_m, 1e-4);
  }
  // The room's corners are concave, the pillar's is convex; the pillar face x = 1 and the wall
  // behind it (y = 4) would meet at (1, 4), far from both segments' ends: no corner.
  ASSERT_EQ(f.corners.size(), 3u);
  EXPECT_EQ(f.corners[0].kind, CornerKind::kConcave);
  EXPECT_TRUE(f.corners[0].point_m.isApprox(room.concave_corners[0], 1e-4));
  EXPECT_EQ(f.corners[1].kind, CornerKind::kConcave);
  EXPECT_TRUE(f.corners[1].point_m.isApprox(room.concave_corners[1], 1e-4));
  EXPECT_EQ(f.corners[2].kind, CornerKind::kConvex);
  EXPECT_TRUE(f.corners[2].point_m.isApprox(room.convex_corners[0], 1e-4));
  for (const Corner& c : f.corners) EXPECT_NEAR(c.angle_rad, std::numbers::pi / 2.0, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(Angles, RoomAtAngle,
                         ::testing::Values(0.0, std::numbers::pi, 2.0, -2.5,
                                           -std::numbers::pi / 2));

TEST(LineExtraction, EndpointsLieOnTheWallsAndEveryReturnOfAWallIsUsed) {
  const PolygonRoom room = MakePolygonRoom(0.0);
  const std::vector<LineSegment> lines = ExtractLines(ScanPolygonRoom(room), {});
  ASSERT_EQ(lines.size(), 6u);
  // Wall x = 6 runs from the corner at −26.57° to the corner at 33.69°: beams −26°..33°.
  EXPECT_EQ(lines[1].first_beam, 90 - 26);
  EXPECT_EQ(lines[1].last_beam, 90 + 33);
  EXPECT_EQ(lines[1].num_points, 60);
  EXPECT_NEAR(lines[1].start_m.x(), 6.0, 1e-4);
  EXPECT_NEAR(lines[1].start_m.y(), 6.0 * std::tan(-26.0 * std::numbers::pi / 180.0), 1e-4);
  EXPECT_NEAR(lines[1].end_m.y(), 6.0 * std::tan(33.0 * std::numbers::pi / 180.0), 1e-4);
}

TEST(LineExtraction, NoReturnNanAndMaxRangeBeamsAreNeverUsed) {
  const PolygonRoom room = MakePolygonRoom(0.0);
  LaserScan scan = ScanPolygonRoom(room);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  // Three beams inside wall x = 6 (about 0.1 m apart there, so the wall stays one run) and the
  // first ten beams of wall y = −3. Were any used, its point would sit at 30 m or be NaN.
  scan.ranges_m[95] = static_cast<float>(scan.max_range_m);
  scan.ranges_m[96] = nan;
  scan.ranges_m[97] = 0.0f;
  for (int i = 0; i < 10; ++i) scan.ranges_m[i] = static_cast<float>(scan.max_range_m) + 1.0f;
  const std::vector<LineSegment> lines = ExtractLines(scan, {});
  ASSERT_EQ(lines.size(), room.visible_lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    ExpectLine(lines[i].line, room.visible_lines[i], 1e-4, 1e-4);
  }
  EXPECT_EQ(lines[0].first_beam, 10);
  EXPECT_EQ(lines[1].num_points, 60 - 3);

  // A usable range below the sensor's drops wall x = 6 (≥ 6 m away) altogether.
  LineExtractionParams near;
  near.max_usable_range_m = 5.9;
  const std::vector<LineSegment> near_lines = ExtractLines(scan, near);
  EXPECT_GE(near_lines.size(), 3u);  // the pillar faces and the wall behind it stay
  for (const LineSegment& s : near_lines) EXPECT_GT(std::abs(s.line.rho_m - 6.0), 0.1);
}

TEST(LineExtraction, AGapSplitsAWallIntoTwoUnmergedSegments) {
  const PolygonRoom room = MakePolygonRoom(0.0, /*door_in_front=*/true);
  const std::vector<LineSegment> lines = ExtractLines(ScanPolygonRoom(room), {});
  std::vector<LineSegment> front;
  for (const LineSegment& s : lines) {
    if (std::abs(s.line.rho_m - 6.0) < 1e-3 && std::abs(s.line.alpha_rad) < 1e-3) {
      front.push_back(s);
    }
  }
  ASSERT_EQ(front.size(), 2u);
  EXPECT_LT(front[0].end_m.y(), -0.5 + 1e-6);
  EXPECT_GT(front[1].start_m.y(), 0.5 - 1e-6);
  EXPECT_EQ(lines.size(), room.visible_lines.size() + 1);
}

TEST(LineExtraction, ShortAndPoorlySupportedSegmentsAreRejected) {
  const PolygonRoom room = MakePolygonRoom(0.0);
  const LaserScan scan = ScanPolygonRoom(room);
  LineExtractionParams strict;
  strict.min_points = 19;  // the walls have 64 and 60 returns, the rest 13, 18, 8 and 18
  EXPECT_EQ(ExtractLines(scan, strict).size(), 2u);
  LineExtractionParams long_only;
  long_only.min_length_m = 1.5;  // the three walls before the pillar are ≥ 2 m, the rest < 1.3 m
  EXPECT_EQ(ExtractLines(scan, long_only).size(), 3u);

  // With 1 cm range noise every wall fits to a few millimetres: all pass the default 3 cm RMS
  // bound and all fail a 0.5 mm one.
  Rng rng(3);
  const LaserScan noisy = ScanPolygonRoom(room, &rng, 0.01, 0.0);
  EXPECT_EQ(ExtractLines(noisy, {}).size(), room.visible_lines.size());
  LineExtractionParams tight;
  tight.max_residual_rms_m = 0.0005;
  EXPECT_TRUE(ExtractLines(noisy, tight).empty());
}

// A split threshold of 3σ cuts walls at noise now and then; the merge puts them back together.
// Without it (no angle difference accepted) half the scans come out with extra segments.
TEST(LineExtraction, MergeJoinsTheWallsThatNoiseSplit) {
  const PolygonRoom room = MakePolygonRoom(0.3);
  auto share_right = [&](const LineExtractionParams& params) {
    Rng rng(21);
    int right = 0;
    for (int k = 0; k < 200; ++k) {
      right += ExtractLines(ScanPolygonRoom(room, &rng, 0.01, 0.0), params).size() ==
               room.visible_lines.size();
    }
    return right / 200.0;
  };
  LineExtractionParams params;
  params.split_distance_m = 0.03;
  EXPECT_GE(share_right(params), 0.95);
  params.merge_max_angle_rad = 0.0;
  EXPECT_LE(share_right(params), 0.6);
}

TEST(LineExtraction, ScansWithTooFewReturnsGiveNothing) {
  EXPECT_TRUE(ExtractFeatures(LaserScan{}).lines.empty());
  LaserScan scan = ScanPolygonRoom(MakePolygonRoom(0.0));
  for (float& r : scan.ranges_m) r = static_cast<float>(scan.max_range_m);
  EXPECT_TRUE(ExtractFeatures(scan).lines.empty());
  scan.ranges_m[40] = scan.ranges_m[41] = scan.ranges_m[42] = 2.0f;  // three returns: too few
  EXPECT_TRUE(ExtractFeatures(scan).lines.empty());
}

TEST(SplitByEndpointFit, PiecesAreDisjointOrderedAndCoverTheRun) {
  const PolygonRoom room = MakePolygonRoom(0.0);
  const std::vector<BeamPoint> points = ScanToBeamPoints(ScanPolygonRoom(room), 30.0);
  const std::vector<PointRange> runs = SplitAtGaps(points, 0.5);
  ASSERT_EQ(runs.size(), 3u);  // walls up to the pillar | the pillar | the wall behind it
  const std::vector<PointRange> pieces = SplitByEndpointFit(points, runs[0], 0.05);
  ASSERT_GE(pieces.size(), 3u);  // one per wall, maybe a corner point on its own
  EXPECT_EQ(pieces.front().begin, runs[0].begin);
  EXPECT_EQ(pieces.back().end, runs[0].end);
  for (std::size_t i = 0; i + 1 < pieces.size(); ++i) EXPECT_EQ(pieces[i].end, pieces[i + 1].begin);
}

}  // namespace
}  // namespace slamkit
