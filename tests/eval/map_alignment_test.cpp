#include "slamkit/eval/map_alignment.hpp"

#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <gtest/gtest.h>

#include "slamkit/eval/map_comparison.hpp"

namespace slamkit {
namespace {

constexpr std::uint8_t kFreePixel = 254, kWallPixel = 0;

// A 12 m × 8 m room at 0.1 m with a wall stub and an L inside (no symmetry to confuse a search),
// in a 16 m × 12 m image whose lower-left corner is at (−2, −2).
OccupancyImage RoomWithStubAndL() {
  OccupancyImage m;
  m.width = 160;
  m.height = 120;
  m.resolution_m = 0.1;
  m.origin_m = {-2.0, -2.0};
  m.pixels.assign(std::size_t(m.width) * m.height, 205);
  auto set = [&](double x, double y, std::uint8_t v) {
    const int col = static_cast<int>(std::floor((x - m.origin_m.x()) / m.resolution_m));
    const int row =
        m.height - 1 - static_cast<int>(std::floor((y - m.origin_m.y()) / m.resolution_m));
    m.pixels[std::size_t(row) * m.width + col] = v;
  };
  for (double x = 0.05; x < 12.0; x += 0.1) {
    for (double y = 0.05; y < 8.0; y += 0.1) set(x, y, kFreePixel);
  }
  for (double t = 0.05; t < 12.0; t += 0.1) set(t, 0.05, kWallPixel), set(t, 7.95, kWallPixel);
  for (double t = 0.05; t < 8.0; t += 0.1) set(0.05, t, kWallPixel), set(11.95, t, kWallPixel);
  for (double t = 0.05; t < 3.0; t += 0.1) set(4.05, t, kWallPixel);         // a stub
  for (double t = 6.0; t < 9.0; t += 0.1) set(t, 5.05, kWallPixel);          // an L
  for (double t = 3.0; t < 5.1; t += 0.1) set(8.95, t, kWallPixel);
  return m;
}

// The second map is the first moved by T: the alignment finds T⁻¹ (second's frame into the
// first's) to within a cell and a cell's turn, and the resampled second then matches the first.
TEST(AlignMaps, RecoversAKnownShiftAndTurn) {
  const OccupancyImage first = RoomWithStubAndL();
  const Pose2 moved(0.43, -0.27, 0.06);
  const OccupancyImage second = ResampleMap(first, first, moved);
  MapComparisonParams tolerant;
  tolerant.dice_tolerance_cells = 1;
  EXPECT_LT(CompareMaps(first, second, tolerant).dice_occupied, 0.5);  // not aligned: poor
  const MapAlignment a = AlignMaps(first, second);
  const Pose2 expected = moved.Inverse();
  EXPECT_NEAR(a.transform.x(), expected.x(), 0.1);
  EXPECT_NEAR(a.transform.y(), expected.y(), 0.1);
  EXPECT_NEAR(a.transform.theta(), expected.theta(), 0.01);
  const OccupancyImage back = ResampleMap(first, second, a.transform);
  EXPECT_GT(CompareMaps(first, back, tolerant).dice_occupied, 0.9);
  EXPECT_GT(a.score, 0.8);
}

TEST(AlignMaps, AMapAgainstItselfIsTheIdentity) {
  const OccupancyImage first = RoomWithStubAndL();
  const MapAlignment a = AlignMaps(first, first);
  EXPECT_EQ(a.transform.vector(), Pose2().vector());
  EXPECT_EQ(a.score, 1.0);
}

TEST(AlignMaps, RefusesOtherResolutionsAndNegativeBounds) {
  const OccupancyImage first = RoomWithStubAndL();
  OccupancyImage coarse = first;
  coarse.resolution_m = 0.2;
  EXPECT_THROW(AlignMaps(first, coarse), std::invalid_argument);
  MapAlignmentParams bad;
  bad.max_shift_m = -1.0;
  EXPECT_THROW(AlignMaps(first, first, bad), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
