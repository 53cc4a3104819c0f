#include "slamkit/io/trajectory_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>

#include "slamkit/io/writers.hpp"

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

class TrajectoryReader : public testing::TempDirTest {
 protected:
  fs::path Write(const std::string& text) const { return WriteFile("poses.txt", text); }
  std::string ErrorOf(const std::string& text) const {
    return testing::InputErrorOf([&] { ReadTrajectory(Write(text)); });
  }
};

TEST_F(TrajectoryReader, ReadsASuiteReferenceOnePosePerScan) {
  const Trajectory reference = ReadTrajectory(fs::path(SLAMKIT_DATASETS_DIR) / "carmen" /
                                              "suite" / "freiburg-101.reference.txt");
  ASSERT_EQ(reference.size(), 292u);
  // 158.415000 0.108623 -0.034410 0.552197
  EXPECT_EQ(reference[0].t_s, 158.415);
  EXPECT_EQ(reference[0].pose.vector(), Eigen::Vector3d(0.108623, -0.034410, 0.552197));
}

TEST_F(TrajectoryReader, ReadsBackTheTumItsWriterWrites) {
  const Trajectory written = {{1.5, Pose2(1.0, -2.0, 0.3)},
                              {2.5, Pose2(-3.25, 4.0, std::numbers::pi - 0.01)},
                              {2.5, Pose2(0.0, 0.0, -2.0)}};  // a repeated time is kept
  const fs::path path = dir_ / "t.tum";
  WriteTumTrajectory(path, written);
  const Trajectory read = ReadTrajectory(path);
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].t_s, written[i].t_s);
    EXPECT_NEAR(read[i].pose.x(), written[i].pose.x(), 1e-12);
    EXPECT_NEAR(read[i].pose.y(), written[i].pose.y(), 1e-12);
    EXPECT_NEAR(read[i].pose.theta(), written[i].pose.theta(), 1e-12);
  }
}

TEST_F(TrajectoryReader, SkipsCommentsAndBlankLines) {
  const Trajectory t =
      ReadTrajectory(Write("# t x y theta\n\n  \n1134860000.25 1 2 0.5\n# end\n"));
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].t_s, 1134860000.25);  // Unix seconds are not a magnitude error
  EXPECT_EQ(t[0].pose.vector(), Eigen::Vector3d(1, 2, 0.5));
}

TEST_F(TrajectoryReader, BadLinesNameTheFileLineAndField) {
  struct Case {
    std::string text, part;
  };
  const Case cases[] = {
      {"0 1 2 0.5\n0 1 2\n", ":2: field 'line': expected `t x y theta`"},
      {"0 1 nan 0.5\n", ":1: field 'y'"},
      {"0 1 2e7 0.5\n", "field 'y': magnitude above"},
      {"0 1 x 0.5\n", ":1: field 'y'"},
      {"0 1 2 0.5 0 0 0 1\n", "field 'z'"},                  // z = 0.5: not planar
      {"0 1 2 0 0.1 0 0 1\n", "field 'qx'"},
      {"0 1 2 0 0 0 0.5 0.5\n", "field 'qw': (qz, qw) is not a unit quaternion"}};
  for (const Case& c : cases) {
    const std::string message = ErrorOf(c.text);
    EXPECT_NE(message.find("poses.txt"), std::string::npos) << c.text << ": " << message;
    EXPECT_NE(message.find(c.part), std::string::npos) << c.text << ": " << message;
  }
}

TEST_F(TrajectoryReader, AFileWithNoPoseSaysWhatItExpected) {
  for (const char* text : {"", "# only a comment\n\n"}) {
    const std::string message = ErrorOf(text);
    EXPECT_NE(message.find("no poses (expected `t x y theta`"), std::string::npos) << message;
  }
  EXPECT_NE(testing::InputErrorOf([&] { ReadTrajectory(dir_ / "missing.txt"); }).find("missing"),
            std::string::npos);
}

}  // namespace
}  // namespace slamkit
