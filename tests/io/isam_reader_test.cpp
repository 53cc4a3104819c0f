#include "slamkit/io/isam_reader.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "slamkit/io/error.hpp"

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;
using testing::Contains;

constexpr const char* kOdometry01 = "ODOMETRY 0 1 0.5 0.01 0.02 0.0001 0 0 4e-06 0 4e-06\n";

class IsamReader : public testing::TempDirTest {
 protected:
  fs::path Write(const std::string& text) const { return WriteFile("log.txt", text); }
  std::string ErrorOf(const std::string& text) const {
    return testing::InputErrorOf([&] { ReadIsamLog(Write(text)); });
  }
};

TEST_F(IsamReader, ReadsVictoriaPark) {
  const IsamLog log =
      ReadIsamLog(fs::path(SLAMKIT_DATASETS_DIR) / "victoria_park" / "victoria_park_isam.txt");
  EXPECT_EQ(log.initial_pose_index, 0);
  EXPECT_TRUE(log.initial_sightings.empty());
  ASSERT_EQ(log.steps.size(), 6968u);
  std::size_t sightings = 0;
  for (const IsamStep& step : log.steps) sightings += step.sightings.size();
  EXPECT_EQ(sightings, 3640u);

  // ODOMETRY 0 1 0.000985144 -3.63222e-10 -1.54136e-06 0.0001 0 0 4e-06 0 4e-06
  const IsamStep& first = log.steps[0];
  EXPECT_EQ(first.pose_index, 1);
  EXPECT_EQ(first.odometry, Eigen::Vector3d(0.000985144, -3.63222e-10, -1.54136e-06));
  EXPECT_EQ(first.odometry_covariance.diagonal(), Eigen::Vector3d(1e-4, 4e-6, 4e-6));
  EXPECT_TRUE(first.sightings.empty());
  // ODOMETRY 3 4 …, then LANDMARK 4 5 11.5387 -3.2007 0.4 0 0.4; the next pose is 6.
  const IsamStep& fourth = log.steps[3];
  EXPECT_EQ(fourth.pose_index, 4);
  ASSERT_EQ(fourth.sightings.size(), 1u);
  EXPECT_EQ(fourth.sightings[0].id, 5);
  EXPECT_EQ(fourth.sightings[0].z, Eigen::Vector2d(11.5387, -3.2007));
  EXPECT_EQ(fourth.sightings[0].R, 0.4 * Eigen::Matrix2d::Identity());
  EXPECT_EQ(log.steps[4].pose_index, 6);
  EXPECT_EQ(log.steps.back().pose_index, 7119);
}

TEST_F(IsamReader, FullCovariancesAndInitialSightings) {
  const IsamLog log =
      ReadIsamLog(Write("# comment\n"
                        "LANDMARK 3 10 1 2 0.5 0.1 0.2\n"
                        "\n"
                        "ODOMETRY 3 4 1 0 0.1 0.04 0.001 0.002 0.09 0.003 0.01\n"
                        "LANDMARK 4 10 0.5 2 0.5 0 0.5\n"
                        "LANDMARK 4 11 3 -1 0.5 0 0.5\n"));
  EXPECT_EQ(log.initial_pose_index, 3);
  ASSERT_EQ(log.initial_sightings.size(), 1u);
  EXPECT_EQ(log.initial_sightings[0].id, 10);
  Eigen::Matrix2d R;
  R << 0.5, 0.1, 0.1, 0.2;
  EXPECT_EQ(log.initial_sightings[0].R, R);
  ASSERT_EQ(log.steps.size(), 1u);
  Eigen::Matrix3d Q;
  Q << 0.04, 0.001, 0.002, 0.001, 0.09, 0.003, 0.002, 0.003, 0.01;
  EXPECT_EQ(log.steps[0].odometry_covariance, Q);
  EXPECT_EQ(log.steps[0].sightings.size(), 2u);
}

TEST_F(IsamReader, RejectsMalformedLinesWithTheirNumber) {
  const std::string ok = kOdometry01;
  EXPECT_TRUE(Contains(ErrorOf(ok + "ODOMETRY 1 2 0.5 abc 0 1 0 0 1 0 1\n"),
                       "log.txt:2: field 'dy': not a number ('abc')"));
  EXPECT_TRUE(Contains(ErrorOf(ok + ok.substr(0, 9) + "1 2 nan 0 0 1 0 0 1 0 1\n"),
                       "log.txt:2: field 'dx': not a finite number"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "POSE 1 0 0 0\n"), "log.txt:2: unknown record 'POSE'"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "ODOMETRY 2 3 0.5 0 0 1 0 0 1 0 1\n"),
                       "log.txt:2: ODOMETRY from pose 2 breaks the chain"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "LANDMARK 0 7 1 1 1 0 1\n"),
                       "log.txt:2: LANDMARK from pose 0 breaks the chain"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "ODOMETRY 1 2 0.5 0 0 1 0 0 1 0\n"),
                       "log.txt:2: field 'c_thetatheta': missing"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "LANDMARK 1 7 1 1 1 0 1 9\n"), "log.txt:2: LANDMARK expects"));
  EXPECT_TRUE(
      Contains(ErrorOf(ok + "LANDMARK 1.5 7 1 1 1 0 1\n"), "log.txt:2: field 'i': not an integer"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "\nLANDMARK 1 7 1 1 1 2 1\n"),
                       "log.txt:3: landmark covariance is not positive definite"));
  EXPECT_TRUE(Contains(ErrorOf("ODOMETRY 0 1 0.5 0 0 1 0 0 0 0 1\n"),
                       "log.txt:1: odometry covariance is not positive definite"));
}

// Issue 8 item 7: absurd magnitudes would run to a map full of NaN.
TEST_F(IsamReader, RejectsValuesOfAbsurdMagnitude) {
  const std::string ok = kOdometry01;
  EXPECT_TRUE(Contains(ErrorOf(ok + "LANDMARK 1 7 1e308 1 1 0 1\n"),
                       "log.txt:2: field 'x': magnitude above 1e+06 m"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "LANDMARK 1 7 1 -2e6 1 0 1\n"),
                       "log.txt:2: field 'y': magnitude above"));
  EXPECT_TRUE(Contains(ErrorOf("ODOMETRY 0 1 1e308 0 0 1 0 0 1 0 1\n"),
                       "log.txt:1: field 'dx': magnitude above"));
  EXPECT_TRUE(Contains(ErrorOf("ODOMETRY 0 1 0 0 1e308 1 0 0 1 0 1\n"),
                       "log.txt:1: field 'dtheta': magnitude above"));
  EXPECT_TRUE(Contains(ErrorOf("ODOMETRY 0 1 0 0 0 1e300 0 0 1 0 1\n"),
                       "log.txt:1: field 'c_xx': magnitude above"));
  EXPECT_TRUE(Contains(ErrorOf(ok + "LANDMARK 1 7 1 1 1 0 1e300\n"),
                       "log.txt:2: field 'c_yy': magnitude above"));
  ReadIsamLog(Write(ok + "LANDMARK 1 7 1e6 -1e6 1e12 0 1e12\n"));  // the bounds themselves
}

// Issue 8 item 8: the CSV reader rejects negative ids, so must this one.
TEST_F(IsamReader, RejectsNegativeLandmarkIds) {
  EXPECT_TRUE(Contains(ErrorOf(std::string(kOdometry01) + "LANDMARK 1 -1 1 1 1 0 1\n"),
                       "log.txt:2: field 'l': negative landmark id (-1)"));
}

// Issue 8 item 11: nothing to process, or not an iSAM log at all.
TEST_F(IsamReader, RejectsInputWithNothingToProcess) {
  EXPECT_TRUE(Contains(ErrorOf(""), "log.txt: no records (expected an iSAM log"));
  EXPECT_TRUE(Contains(ErrorOf("# only\n\n  \n"), "log.txt: no records (expected an iSAM log"));
  EXPECT_TRUE(Contains(ErrorOf("#ROSBAG V2.0\nE\x01\x02\n"),
                       "log.txt:1: a ROS bag (#ROSBAG header), expected an iSAM log"));
  EXPECT_TRUE(Contains(ErrorOf(std::string("\x89PNG\r\n\x1a\n\0\0", 10)),
                       "log.txt:1: unknown record '\\x89PNG' (expected ODOMETRY or LANDMARK"));
}

TEST_F(IsamReader, MissingFileNamesIt) {
  try {
    ReadIsamLog(dir_ / "absent.txt");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_TRUE(Contains(e.what(), "absent.txt"));
  }
}

}  // namespace
}  // namespace slamkit
