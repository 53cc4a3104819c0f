#include "slamkit/report/figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"

#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

struct PngSize {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

std::uint32_t BigEndian32(const unsigned char* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}

// The image size from the IHDR chunk, which the PNG standard requires to come first.
PngSize ReadPngSize(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 24> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  EXPECT_EQ(in.gcount(), 24) << path;
  const std::array<unsigned char, 8> signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(std::equal(signature.begin(), signature.end(), head.begin())) << path;
  EXPECT_EQ(std::string(head.begin() + 12, head.begin() + 16), "IHDR") << path;
  return {BigEndian32(&head[16]), BigEndian32(&head[20])};
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
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
    const Eigen::Vector2d p(rng.Uniform(-25.0, 25.0), rng.Uniform(-12.0, 12.0));
    data.true_landmarks.landmarks.push_back({i, p});
    MappedLandmark m;
    m.source_id = i;
    m.position_m = p + Eigen::Vector2d(rng.Normal(0.0, 0.2), rng.Normal(0.0, 0.2));
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
    const Eigen::Vector2d lambda(rng.Uniform(0.01, 4.0), rng.Uniform(0.01, 4.0));
    const Eigen::Matrix2d cov = R * lambda.asDiagonal() * R.transpose();
    const Eigen::Vector2d mean(rng.Uniform(-50.0, 50.0), rng.Uniform(-50.0, 50.0));
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
