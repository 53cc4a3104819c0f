#include "slamkit/report/figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <numbers>
#include <stdexcept>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>
#include <png.h>

#include "slamkit/core/rng.hpp"

#include "common/ordered_draws.hpp"
#include "common/temp_dir.hpp"
#include "png_pixels.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

using testing::Filled;
using testing::NotADrawnFigure;
using testing::PngSize;
using testing::ReadPngSize;
using testing::ReadText;
using testing::RgbaImage;

// Strongly blue, red, green or near-black pixels: the pens "b", "r", "g" and "k" of the figures.
bool IsBlue(const std::uint8_t* p) { return p[2] > 180 && p[0] < 90 && p[1] < 90; }
bool IsRed(const std::uint8_t* p) { return p[0] > 180 && p[1] < 90 && p[2] < 90; }
bool IsGreen(const std::uint8_t* p) { return p[1] > 150 && p[0] < 90 && p[2] < 90; }
bool IsBlack(const std::uint8_t* p) { return p[0] < 40 && p[1] < 40 && p[2] < 40; }

// Pixels of a colour in each horizontal third of the image (top, middle, bottom): the rows of
// the consistency figure's three panels (ANEES, position RMSE, heading RMSE).
std::array<int, 3> PerThird(const RgbaImage& image, bool (*is)(const std::uint8_t*)) {
  std::array<int, 3> n{};
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (is(&image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)])) {
        ++n[std::min(2, 3 * y / image.height)];
      }
    }
  }
  return n;
}

PathFigureData SamplePathData(int landmarks) {
  PathFigureData data;
  data.title = "loop_closure {test} 100%";
  data.width_px = 640;
  data.height_px = 480;
  Rng rng(11);
  for (int i = 0; i <= 200; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 200;
    data.truth.push_back({0.1 * i, Pose2(20.0 * std::cos(a), 8.0 * std::sin(a), a)});
    data.estimate.push_back({0.1 * i, Pose2(20.3 * std::cos(a), 8.2 * std::sin(a), a)});
  }
  for (int i = 0; i < landmarks; ++i) {
    const Eigen::Vector2d p = testing::UniformVector2(rng, -25.0, 25.0, -12.0, 12.0);
    data.true_landmarks.landmarks.push_back({i, p});
    MappedLandmark m;
    m.source_id = i;
    m.position_m = p + testing::NormalVector2(rng, 0.2, 0.2);
    m.covariance << 0.04, 0.01, 0.01, 0.02;
    data.map.landmarks.push_back(m);
  }
  return data;
}

ConsistencyFigureData SampleConsistencyData() {
  ConsistencyFigureData data;
  data.title = "consistency";
  data.width_px = 800;
  data.height_px = 700;
  data.band_lo = 2.5;
  data.band_hi = 3.5;
  for (int i = 0; i < 100; ++i) {
    data.t_s.push_back(0.1 * i);
    data.anees.push_back(3.0 + std::sin(0.2 * i));
    data.position_rmse_m.push_back(0.05 + 0.002 * i);
    data.heading_rmse_rad.push_back(0.01 + 0.0001 * i);
  }
  return data;
}

class Figures : public testing::TempDirTest {
 protected:

  int FilesInDir() const {
    return static_cast<int>(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
};

TEST_F(Figures, PathFigureWritesPngOfRequestedSizeAndSvg) {
  const PathFigureData data = SamplePathData(40);
  WritePathFigure(dir_ / "map.png", data);
  const PngSize size = ReadPngSize(dir_ / "map.png");
  EXPECT_EQ(size.width, 640u);
  EXPECT_EQ(size.height, 480u);
  EXPECT_GT(fs::file_size(dir_ / "map.png"), 2000u);
  WritePathFigure(dir_ / "map.svg", data);
  EXPECT_NE(ReadText(dir_ / "map.svg").find("<svg"), std::string::npos);
  EXPECT_EQ(FilesInDir(), 2);  // no temporaries left behind
}

TEST_F(Figures, DrawnFigureCheckRejectsBlankAndSingleColourImages) {
  testing::WriteRgbaPng(dir_ / "white.png", Filled(640, 480, {255, 255, 255, 255}));
  testing::WriteRgbaPng(dir_ / "grey.png", Filled(640, 480, {90, 90, 90, 255}));
  RgbaImage dot = Filled(640, 480, {255, 255, 255, 255});
  for (int i = 0; i < 12; ++i) dot.rgba[4 * (i * 641)] = static_cast<std::uint8_t>(20 * i);
  testing::WriteRgbaPng(dir_ / "dots.png", dot);
  for (const char* name : {"white.png", "grey.png", "dots.png"}) {
    const RgbaImage image = testing::ReadRgbaPng(dir_ / name);
    EXPECT_EQ(image.width, 640);
    EXPECT_NE(NotADrawnFigure(image), "") << name;
    EXPECT_EQ(PerThird(image, IsBlue), (std::array<int, 3>{0, 0, 0})) << name;
  }
}

TEST_F(Figures, PathFigureDrawsEveryLayerInItsColour) {
  WritePathFigure(dir_ / "map.png", SamplePathData(40));
  const RgbaImage image = testing::ReadRgbaPng(dir_ / "map.png");
  ASSERT_EQ(image.width, 640);
  ASSERT_EQ(image.height, 480);
  EXPECT_EQ(NotADrawnFigure(image), "");
  int blue = 0, red = 0, green = 0, black = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    const std::uint8_t* p = &image.rgba[i];
    blue += IsBlue(p) ? 1 : 0;
    red += IsRed(p) ? 1 : 0;
    green += IsGreen(p) ? 1 : 0;
    black += IsBlack(p) ? 1 : 0;
  }
  EXPECT_GT(blue, 300);   // the estimated path (a 2-px line around a 40 m × 16 m ellipse)
  EXPECT_GT(black, 300);  // the true path, the frame, the text
  EXPECT_GT(red, 40);     // 40 estimated landmarks and their ellipses
  EXPECT_GT(green, 40);   // 40 true landmarks
}

// SWSLAM's chosen waypoints: filled magenta discs, and the legend's entry; nothing magenta
// without them.
TEST_F(Figures, PathFigureMarksTheGivenPoints) {
  PathFigureData data = SamplePathData(40);
  WritePathFigure(dir_ / "plain.png", data);
  data.markers_m = {{0.0, 0.0}, {10.0, 5.0}, {-10.0, -5.0}};
  WritePathFigure(dir_ / "marked.png", data);
  auto magenta = [](const RgbaImage& image) {
    int n = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
      const std::uint8_t* p = &image.rgba[i];
      n += p[0] > 180 && p[1] < 90 && p[2] > 180 ? 1 : 0;
    }
    return n;
  };
  EXPECT_EQ(magenta(testing::ReadRgbaPng(dir_ / "plain.png")), 0);
  EXPECT_GT(magenta(testing::ReadRgbaPng(dir_ / "marked.png")), 4 * 30);  // three discs and the legend's
}

// The data are drawn where they belong: each series lands in its own panel's third of the image,
// and a missing series leaves its panel without a line.
TEST_F(Figures, ConsistencyFigureDrawsEachSeriesInItsPanel) {
  const ConsistencyFigureData data = SampleConsistencyData();
  WriteConsistencyFigure(dir_ / "all.png", data);
  const RgbaImage all = testing::ReadRgbaPng(dir_ / "all.png");
  EXPECT_EQ(NotADrawnFigure(all), "");
  const std::array<int, 3> blue = PerThird(all, IsBlue);
  for (int panel = 0; panel < 3; ++panel) EXPECT_GT(blue[panel], 200) << "panel " << panel;
  const std::array<int, 3> red = PerThird(all, IsRed);  // the ANEES band's dashed lines
  EXPECT_GT(red[0], 200);
  EXPECT_EQ(red[1] + red[2], 0);

  ConsistencyFigureData position_only = data;
  position_only.anees.clear();
  position_only.heading_rmse_rad.clear();
  position_only.band_lo = position_only.band_hi = 0.0;
  WriteConsistencyFigure(dir_ / "position.png", position_only);
  const RgbaImage position = testing::ReadRgbaPng(dir_ / "position.png");
  EXPECT_EQ(NotADrawnFigure(position), "");
  const std::array<int, 3> only = PerThird(position, IsBlue);
  EXPECT_EQ(only[0], 0);
  EXPECT_GT(only[1], 200);
  EXPECT_EQ(only[2], 0);
  EXPECT_EQ(PerThird(position, IsRed), (std::array<int, 3>{0, 0, 0}));
}

TEST_F(Figures, PathFigureWithoutTruthOrLandmarks) {
  PathFigureData data = SamplePathData(0);
  data.truth.clear();
  WritePathFigure(dir_ / "estimate_only.PNG", data);  // extension matched in any case
  EXPECT_EQ(ReadPngSize(dir_ / "estimate_only.PNG").width, 640u);
  WritePathFigure(dir_ / "nothing.png", PathFigureData{});
  EXPECT_EQ(ReadPngSize(dir_ / "nothing.png").height, 1000u);
}

TEST_F(Figures, PathFigureWithThousandsOfLandmarks) {
  WritePathFigure(dir_ / "big.png", SamplePathData(3000));
  EXPECT_EQ(ReadPngSize(dir_ / "big.png").width, 640u);
}

TEST_F(Figures, ConsistencyFigureWritesPngAndSvg) {
  const ConsistencyFigureData data = SampleConsistencyData();
  WriteConsistencyFigure(dir_ / "consistency.png", data);
  const PngSize size = ReadPngSize(dir_ / "consistency.png");
  EXPECT_EQ(size.width, 800u);
  EXPECT_EQ(size.height, 700u);
  WriteConsistencyFigure(dir_ / "consistency.svg", data);
  EXPECT_NE(ReadText(dir_ / "consistency.svg").find("<svg"), std::string::npos);
  WriteConsistencyFigure(dir_ / "empty.png", ConsistencyFigureData{});
  EXPECT_EQ(FilesInDir(), 3);
}

TEST_F(Figures, ConsistencySeriesOfWrongLengthIsRejected) {
  ConsistencyFigureData data = SampleConsistencyData();
  data.position_rmse_m.pop_back();
  EXPECT_THROW(WriteConsistencyFigure(dir_ / "c.png", data), std::invalid_argument);
  EXPECT_EQ(FilesInDir(), 0);
}

TEST_F(Figures, UnknownExtensionIsRejected) {
  EXPECT_THROW(WritePathFigure(dir_ / "map.pdf", SamplePathData(3)), std::invalid_argument);
  EXPECT_THROW(WriteConsistencyFigure(dir_ / "c", SampleConsistencyData()),
               std::invalid_argument);
  EXPECT_EQ(FilesInDir(), 0);
}

TEST_F(Figures, UnwritablePathThrowsNamingItAndLeavesNoFile) {
  const fs::path missing_dir = dir_ / "no_such_dir" / "map.png";
  try {
    WritePathFigure(missing_dir, SamplePathData(3));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing_dir.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(missing_dir));
  // A directory in the way: the rename fails and the temporary beside it is removed.
  fs::create_directory(dir_ / "taken.svg");
  EXPECT_THROW(WriteConsistencyFigure(dir_ / "taken.svg", SampleConsistencyData()),
               std::runtime_error);
  EXPECT_TRUE(fs::is_directory(dir_ / "taken.svg"));
  EXPECT_EQ(FilesInDir(), 1);
}

TEST_F(Figures, ExistingFileIsReplaced) {
  const fs::path path = dir_ / "map.png";
  std::ofstream(path) << "old";
  WritePathFigure(path, SamplePathData(5));
  EXPECT_EQ(ReadPngSize(path).width, 640u);
  EXPECT_EQ(FilesInDir(), 1);
}

TEST(CovarianceEllipse, PointsLieOnTheSigmaContourAndReachTheMajorAxis) {
  Rng rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const double angle = rng.Uniform(-std::numbers::pi, std::numbers::pi);
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(angle).toRotationMatrix();
    const Eigen::Vector2d lambda = testing::UniformVector2(rng, 0.01, 4.0, 0.01, 4.0);
    const Eigen::Matrix2d cov = R * lambda.asDiagonal() * R.transpose();
    const Eigen::Vector2d mean = testing::UniformVector2(rng, -50.0, 50.0, -50.0, 50.0);
    const double sigma = rng.Uniform(0.5, 3.0);
    const int points = 7 + trial % 40;
    const std::vector<Eigen::Vector2d> ring = CovarianceEllipse(mean, cov, sigma, points);
    ASSERT_EQ(static_cast<int>(ring.size()), points);

    const Eigen::Matrix2d info = cov.inverse();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(cov);
    const Eigen::Vector2d major = eigen.eigenvectors().col(1);
    double extreme = 0.0;
    for (const Eigen::Vector2d& p : ring) {
      const Eigen::Vector2d d = p - mean;
      EXPECT_NEAR(std::sqrt(d.dot(info * d)), sigma, 1e-9);
      extreme = std::max(extreme, std::abs(major.dot(d)));
    }
    EXPECT_NEAR(extreme, sigma * std::sqrt(eigen.eigenvalues()(1)), 1e-9);
  }
}

TEST(CovarianceEllipse, DegenerateCovarianceGivesFinitePoints) {
  Eigen::Matrix2d cov;
  cov << 1.0, 1.0, 1.0, 1.0 - 1e-17;  // rank one, eigenvalue rounding may go negative
  for (const Eigen::Vector2d& p : CovarianceEllipse(Eigen::Vector2d(1.0, 2.0), cov, 2.0, 36)) {
    EXPECT_TRUE(p.allFinite());
    EXPECT_NEAR(p.x() - 1.0, p.y() - 2.0, 1e-9);  // on the line through the mean along (1, 1)
  }
}

}  // namespace
}  // namespace slamkit
