// The line-and-corner map figure and the series figure: they write decodable images, draw what
// they are given, stay fast on a million scan points and reject what they cannot write.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <numbers>
#include <stdexcept>
#include <string>

#include "common/temp_dir.hpp"
#include "png_pixels.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/report/figures.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;
using testing::ReadRgbaPng;
using testing::RgbaImage;

// A 20 m × 10 m room, its walls mapped slightly off, scan points along them, a loop inside.
LineMapFigureData SampleRoom(int points) {
  LineMapFigureData data;
  data.title = "room {test} 100%";
  data.width_px = 800;
  data.height_px = 600;
  const Eigen::Vector2d c[] = {{0, 0}, {20, 0}, {20, 10}, {0, 10}};
  for (int i = 0; i < 4; ++i) {
    data.walls.push_back({c[i], c[(i + 1) % 4]});
    data.lines.push_back({c[i] + Eigen::Vector2d(0.1, 0.1), c[(i + 1) % 4] * 0.98});
    data.corners.push_back(c[i] + Eigen::Vector2d(0.05, -0.05));
  }
  Rng rng(3);
  for (int i = 0; i < points; ++i) {
    const Segment2& wall = data.walls[i % 4];
    const double s = rng.Uniform(0.0, 1.0);
    data.points.push_back(wall.a + s * (wall.b - wall.a) + testing::NormalVector2(rng, 0.02, 0.02));
  }
  for (int i = 0; i <= 100; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 100;
    data.truth.push_back({0.1 * i, Pose2(10 + 6 * std::cos(a), 5 + 3 * std::sin(a), a)});
    data.estimate.push_back({0.1 * i, Pose2(10 + 6.1 * std::cos(a), 5 + 3 * std::sin(a), a)});
    data.odometry.push_back({0.1 * i, Pose2(10 + 7 * std::cos(a), 5 + 3.5 * std::sin(a), a)});
  }
  return data;
}

int CountPixels(const RgbaImage& image, bool (*is)(const std::uint8_t*)) {
  int n = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) n += is(image.At(x, y)) ? 1 : 0;
  }
  return n;
}

bool IsRed(const std::uint8_t* p) { return p[0] > 180 && p[1] < 90 && p[2] < 90; }
bool IsBlue(const std::uint8_t* p) { return p[2] > 180 && p[0] < 90 && p[1] < 90; }
bool IsGreen(const std::uint8_t* p) { return p[1] > 100 && p[0] < 90 && p[2] < 90; }

class LineMapFigure : public testing::TempDirTest {};

TEST_F(LineMapFigure, WritesAPngOfItsSizeWithLinesCornersAndPaths) {
  WriteLineMapFigure(dir_ / "map.png", SampleRoom(2000));
  const RgbaImage image = ReadRgbaPng(dir_ / "map.png");
  ASSERT_EQ(image.width, 800);
  ASSERT_EQ(image.height, 600);
  EXPECT_GT(CountPixels(image, IsRed), 1000);  // four bold mapped lines around the room
  EXPECT_GT(CountPixels(image, IsBlue), 300);  // the estimated loop
  EXPECT_GT(CountPixels(image, IsGreen), 10);  // the corner markers
  // Without lines, corners and estimate, none of their colours.
  LineMapFigureData bare = SampleRoom(2000);
  bare.lines.clear();
  bare.corners.clear();
  bare.estimate.clear();
  WriteLineMapFigure(dir_ / "bare.png", bare);
  const RgbaImage bare_image = ReadRgbaPng(dir_ / "bare.png");
  EXPECT_EQ(CountPixels(bare_image, IsRed), 0);
  EXPECT_EQ(CountPixels(bare_image, IsBlue), 0);
  EXPECT_EQ(CountPixels(bare_image, IsGreen), 0);
}

TEST_F(LineMapFigure, AMillionPointsAreDecimatedAndStayFast) {
  const LineMapFigureData data = SampleRoom(1'000'000);
  const auto start = std::chrono::steady_clock::now();
  WriteLineMapFigure(dir_ / "big.png", data);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(ReadRgbaPng(dir_ / "big.png").width, 800);
  EXPECT_LT(seconds, 5.0);  // undecimated, MathGL takes far longer on a million markers
}

TEST_F(LineMapFigure, SvgEmptyDataAndBadExtension) {
  WriteLineMapFigure(dir_ / "map.svg", SampleRoom(100));
  EXPECT_NE(testing::ReadText(dir_ / "map.svg").find("<svg"), std::string::npos);
  WriteLineMapFigure(dir_ / "empty.PNG", LineMapFigureData{});
  EXPECT_EQ(ReadRgbaPng(dir_ / "empty.PNG").height, 1000);
  EXPECT_THROW(WriteLineMapFigure(dir_ / "map.pdf", SampleRoom(10)), std::invalid_argument);
  EXPECT_THROW(WriteLineMapFigure(dir_ / "no_dir" / "map.png", SampleRoom(10)), std::runtime_error);
  EXPECT_FALSE(fs::exists(dir_ / "map.pdf"));
}

TEST_F(LineMapFigure, SeriesFigureDrawsEachCurveAndChecksLengths) {
  SeriesFigureData data;
  data.title = "accumulated SLAM time";
  data.x_label = "t [s]";
  data.y_label = "time [s]";
  data.width_px = 700;
  data.height_px = 500;
  Series up{"all", {}, {}};
  Series flat{"band", {}, {}, 1, true};
  for (int i = 0; i < 50; ++i) {
    up.x.push_back(i);
    up.y.push_back(0.1 * i);
    flat.x.push_back(i);
    flat.y.push_back(2.0);
  }
  data.series = {up, flat};
  WriteSeriesFigure(dir_ / "s.png", data);
  const RgbaImage image = ReadRgbaPng(dir_ / "s.png");
  ASSERT_EQ(image.width, 700);
  EXPECT_GT(CountPixels(image, IsBlue), 200);
  EXPECT_GT(CountPixels(image, IsRed), 100);
  data.series[1].y.pop_back();
  EXPECT_THROW(WriteSeriesFigure(dir_ / "t.png", data), std::invalid_argument);
  EXPECT_FALSE(fs::exists(dir_ / "t.png"));
  EXPECT_THROW(WriteSeriesFigure(dir_ / "t.jpg", SeriesFigureData{}), std::invalid_argument);
}

// A series with a marker is its points alone: two far-apart landmarks ink a few pixels each,
// where the same two points as a line ink the whole diagonal between them.
TEST_F(LineMapFigure, SeriesWithAMarkerDrawsPointsWithoutALine) {
  SeriesFigureData data;
  data.width_px = 700;
  data.height_px = 500;
  data.series = {Series{"landmarks", {0.0, 10.0}, {0.0, 10.0}, 2, false, 'o'}};
  WriteSeriesFigure(dir_ / "points.png", data);
  const long points = CountPixels(ReadRgbaPng(dir_ / "points.png"), IsGreen);
  data.series[0].marker = 0;
  WriteSeriesFigure(dir_ / "line.png", data);
  const long line = CountPixels(ReadRgbaPng(dir_ / "line.png"), IsGreen);
  EXPECT_GT(points, 10);
  EXPECT_LT(3 * points, line);
}

}  // namespace
}  // namespace slamkit
