#include "slamkit/io/writers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "slamkit/io/landmark_csv.hpp"

#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

class Writers : public testing::TempDirTest {
 protected:

  static std::vector<std::string> Lines(const fs::path& path) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }
  static std::string Read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }
};

TEST_F(Writers, TumLineFormat) {
  const fs::path path = dir_ / "traj.tum";
  WriteTumTrajectory(path, {{1.25, Pose2(0.1, 2.0, 0.0)}, {2.0, Pose2(-3.5, 1e-3, 0.5)}});
  const std::vector<std::string> lines = Lines(path);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "1.250000000 0.1 2 0 0 0 0 1");
  std::istringstream fields(lines[1]);
  double v[8];
  for (double& x : v) ASSERT_TRUE(fields >> x);
  std::string extra;
  EXPECT_FALSE(fields >> extra);
  EXPECT_EQ(v[0], 2.0);
  EXPECT_EQ(v[1], -3.5);
  EXPECT_EQ(v[2], 1e-3);  // exact round trip
  EXPECT_EQ(v[3], 0.0);
  EXPECT_EQ(v[4], 0.0);
  EXPECT_EQ(v[5], 0.0);
  EXPECT_EQ(v[6], std::sin(0.25));
  EXPECT_EQ(v[7], std::cos(0.25));
}

TEST_F(Writers, TumQuaternionEncodesYaw) {
  const fs::path path = dir_ / "traj.tum";
  Trajectory trajectory;
  for (int i = 0; i < 50; ++i) trajectory.push_back({0.1 * i, Pose2(0.0, 0.0, -3.1 + 0.125 * i)});
  WriteTumTrajectory(path, trajectory);
  const std::vector<std::string> lines = Lines(path);
  ASSERT_EQ(lines.size(), trajectory.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::istringstream fields(lines[i]);
    double t, x, y, z, qx, qy, qz, qw;
    ASSERT_TRUE(fields >> t >> x >> y >> z >> qx >> qy >> qz >> qw);
    EXPECT_NEAR(t, trajectory[i].t_s, 1e-9);
    EXPECT_NEAR(qz * qz + qw * qw, 1.0, 1e-15);
    EXPECT_GE(qw, 0.0);
    EXPECT_NEAR(2.0 * std::atan2(qz, qw), trajectory[i].pose.theta(), 1e-12);
  }
}

TEST_F(Writers, LandmarkMapCsv) {
  LandmarkMap map;
  Eigen::Matrix2d cov;
  cov << 0.25, -0.01, -0.01, 1.0 / 3.0;
  map.landmarks = {{4, {1.5, -2.0}, cov}, {kNoLandmark, {0.0, 7.0}, Eigen::Matrix2d::Identity()}};
  const fs::path path = dir_ / "map.csv";
  WriteLandmarkMapCsv(path, map);
  const std::vector<std::string> lines = Lines(path);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "source_id,x_m,y_m,cov_xx,cov_xy,cov_yy");
  EXPECT_EQ(lines[1], "4,1.5,-2,0.25,-0.01,0.3333333333333333");
  EXPECT_EQ(lines[2], "-1,0,7,1,0,1");
}

TEST_F(Writers, LandmarkWorldCsvRoundTrips) {
  LandmarkWorld world;
  world.landmarks = {{0, {0.1, 0.2}}, {9, {-1.0 / 3.0, 1e10}}, {3, {std::numbers::pi, -0.0}}};
  const fs::path path = dir_ / "world.csv";
  WriteLandmarkWorldCsv(path, world);
  EXPECT_EQ(Lines(path)[0], "id,x_m,y_m");
  const LandmarkWorld back = ReadLandmarkCsv(path);
  ASSERT_EQ(back.landmarks.size(), world.landmarks.size());
  for (std::size_t i = 0; i < world.landmarks.size(); ++i) {
    EXPECT_EQ(back.landmarks[i].id, world.landmarks[i].id);
    EXPECT_EQ(back.landmarks[i].position_m, world.landmarks[i].position_m);
  }
}

TEST_F(Writers, JsonIsPrettyAndRoundTrips) {
  const nlohmann::json json = {{"name", "run"}, {"rmse_m", 0.1 + 0.2}, {"values", {1, 2}}};
  const fs::path path = dir_ / "out.json";
  WriteJson(path, json);
  const std::string text = Read(path);
  EXPECT_EQ(text, json.dump(2) + "\n");
  EXPECT_NE(text.find("\n  \"name\": \"run\""), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(text)["rmse_m"].get<double>(), 0.1 + 0.2);
}

}  // namespace
}  // namespace slamkit
