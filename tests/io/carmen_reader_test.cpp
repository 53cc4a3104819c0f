#include "slamkit/io/carmen_reader.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "slamkit/core/angle.hpp"

#include "carmen_log_fixture.hpp"
#include "common/pose_expect.hpp"

// The CARMEN reader on the real logs and on hand-written records: what it reads. What it rejects
// is in carmen_reader_errors_test.cpp.
namespace slamkit {
namespace {

namespace fs = std::filesystem;
using carmen_test::CarmenReader;
using carmen_test::Flaser;
using carmen_test::Odom;
using testing::Contains;
using testing::ExpectSamePose;

const fs::path kCarmenDir = fs::path(SLAMKIT_DATASETS_DIR) / "carmen";

TEST_F(CarmenReader, IntelClockJitterIsAcceptedButNotALargerStepBack) {
  // Line 26 is ODOM at 976052858.404130, line 28 ODOM at 976052858.139632 (0.26 s back).
  CarmenReadOptions strict;
  strict.max_time_step_back_s = 0.1;
  EXPECT_TRUE(Contains(ErrorOf(kCarmenDir / "intel.clf", strict),
                       "intel.clf:28: ODOM field 'timestamp': time goes backwards "
                       "(976052858.139632 < 976052858.404130 on line 26)"));
}

TEST_F(CarmenReader, ReadsIntel) {
  CarmenReadOptions options;
  options.odometry_from_scan_fields = false;  // interpolation is checked on scan 338 below
  const CarmenLog log = ReadCarmenLog(kCarmenDir / "intel.clf", options);
  ASSERT_EQ(log.scans.size(), 13631u);
  EXPECT_EQ(log.odometry.size(), 26915u);
  EXPECT_EQ(log.skipped_lines, 0);
  EXPECT_EQ(log.time_steps_back, 602 + 631);
  EXPECT_EQ(log.params.at("robot_frontlaser_offset"), "0.0");
  int no_returns = 0;
  int scans_back = 0;
  for (std::size_t k = 0; k < log.scans.size(); ++k) {
    const LaserScan& scan = log.scans[k];
    ASSERT_EQ(scan.ranges_m.size(), 180u);
    EXPECT_EQ(scan.max_range_m, double(81.83f));  // no PARAM: the largest reading
    for (int i = 0; i < 180; ++i) no_returns += scan.IsReturn(i) ? 0 : 1;
    if (k > 0 && scan.t_s < log.scans[k - 1].t_s) ++scans_back;
  }
  EXPECT_EQ(no_returns, 68313);  // every 81.83 in the FLASER lines
  EXPECT_EQ(scans_back, 631);    // log order is kept, not sorted by time
  EXPECT_DOUBLE_EQ(log.scans[0].angle_min_rad, -M_PI / 2.0);
  EXPECT_DOUBLE_EQ(log.scans[0].BeamAngle(179), DegToRad(89.0));
  EXPECT_EQ(log.scans[0].ranges_m[0], 1.07f);
  EXPECT_EQ(log.scans[0].t_s, 976052857.337530);

  // Line 1014, scan 338: FLASER ... 3.795 -1.166 -0.420354 (twice) 976052923.798885, between
  // ODOM 3.795 -1.166 -0.420354 ... 976052923.798630 (line 1013) and
  // ODOM 3.821 -1.177 -0.414208 ... 976052923.799573 (line 1015).
  const LaserScan& scan = log.scans[338];
  EXPECT_EQ(scan.t_s, 976052923.798885);
  const double s = (976052923.798885 - 976052923.798630) / (976052923.799573 - 976052923.798630);
  EXPECT_NEAR(s, 0.2704, 1e-3);
  EXPECT_NEAR(scan.odometry.x(), 3.795 + s * 0.026, 1e-9);
  EXPECT_NEAR(scan.odometry.y(), -1.166 - s * 0.011, 1e-9);
  EXPECT_NEAR(scan.odometry.theta(), -0.420354 + s * 0.006146, 1e-9);
  ExpectSamePose(scan.logged_pose, Pose2(3.795, -1.166, -0.420354));
}

TEST_F(CarmenReader, IntelScanFieldsAreTheLatestOdomRecord) {
  const CarmenLog log = ReadCarmenLog(kCarmenDir / "intel.clf");
  ASSERT_EQ(log.scans.size(), 13631u);
  ExpectSamePose(log.scans[338].odometry, Pose2(3.795, -1.166, -0.420354));
  // The scan on line 1035 is stamped 976052925.496700, after the ODOM on line 1036
  // (976052925.373527), yet its odometry fields are those of the ODOM on line 1034.
  EXPECT_EQ(log.scans[345].t_s, 976052925.496700);
  ExpectSamePose(log.scans[345].odometry, Pose2(4.166, -1.339, -0.475664));
}

TEST_F(CarmenReader, ReadsCsailGzip) {
  const CarmenLog log = ReadCarmenLog(kCarmenDir / "csail-corrected.log.gz");
  ASSERT_EQ(log.scans.size(), 406u);
  EXPECT_EQ(log.odometry.size(), 2394u);
  EXPECT_EQ(log.params.at("laser_front_laser_fov"), "3.14159");
  const LaserScan& scan = log.scans[0];
  ASSERT_EQ(scan.ranges_m.size(), 361u);
  // PARAM robot_front_laser_max 50, but readings reach 81.91 (the laser's no-return value): the
  // PARAM is not the laser's range, the largest reading is.
  EXPECT_EQ(scan.max_range_m, double(81.91f));
  ASSERT_EQ(log.notes.size(), 1u);
  EXPECT_NE(log.notes[0].find("PARAM max range 50 m is not the laser's"), std::string::npos);
  EXPECT_FALSE(scan.IsReturn(0));     // 81.91
  EXPECT_DOUBLE_EQ(scan.angle_min_rad, -3.14159 / 2.0);
  EXPECT_DOUBLE_EQ(scan.angle_increment_rad, 3.14159 / 360.0);  // radians, both ends included
}

TEST_F(CarmenReader, ReadsIntelGfs) {
  // GMapping wrote garbage into this log's ODOM timestamps (1.13 after 2493.48, denormals).
  EXPECT_TRUE(Contains(ErrorOf(kCarmenDir / "intel.gfs.log"), "time goes backwards"));
  CarmenReadOptions options;
  options.max_time_step_back_s = std::numeric_limits<double>::infinity();
  const CarmenLog log = ReadCarmenLog(kCarmenDir / "intel.gfs.log", options);
  EXPECT_EQ(log.scans.size(), 910u);
  EXPECT_EQ(log.odometry.size(), 14541u);
}

TEST_F(CarmenReader, InterpolatesOdometryAtTheScanTime) {
  // Times from 10 s: a timestamp below 1e-6 s is "none" and places no record in time.
  const std::string text = Flaser(9) + Odom(0, 0, 0, 10) + Flaser(10.25) + Odom(1, 0, 0.2, 11) +
                           Flaser(11) + Flaser(12);
  CarmenReadOptions interpolate;
  interpolate.odometry_from_scan_fields = false;
  const CarmenLog log = ReadCarmenLog(Write(text), interpolate);
  ASSERT_EQ(log.scans.size(), 4u);
  ASSERT_EQ(log.odometry.size(), 2u);
  EXPECT_EQ(log.odometry[1].t_s, 11.0);
  EXPECT_TRUE(log.scans[1].odometry.vector().isApprox(Eigen::Vector3d(0.25, 0, 0.05), 1e-12));
  ExpectSamePose(log.scans[1].logged_pose, Pose2(9, 8, 0.7));
  ExpectSamePose(log.scans[0].odometry, Pose2(0, 0, 0));    // before the first record
  ExpectSamePose(log.scans[2].odometry, Pose2(1, 0, 0.2));  // exactly on a record
  ExpectSamePose(log.scans[3].odometry, Pose2(1, 0, 0.2));  // after the last
  EXPECT_EQ(log.scans[0].ranges_m, (std::vector<float>{1.5f, 2.5f, 81.83f}));
  EXPECT_TRUE(log.scans[0].IsReturn(1));
  EXPECT_FALSE(log.scans[0].IsReturn(2));

  CarmenReadOptions options;
  options.odometry_from_scan_fields = true;
  ExpectSamePose(ReadCarmenLog(Write(text), options).scans[1].odometry, Pose2(9, 8, 0.7));
}

TEST_F(CarmenReader, InterpolatesHeadingAcrossThePiWrap) {
  // From 3.0 to -3.0 rad is +0.283 rad through π, not -6 rad through 0.
  CarmenReadOptions interpolate;
  interpolate.odometry_from_scan_fields = false;
  const CarmenLog log = ReadCarmenLog(
      Write(Odom(0, 0, 3.0, 10) + Odom(0, 0, -3.0, 11) + Flaser(10.25) + Flaser(10.5)),
      interpolate);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_NEAR(log.scans[0].odometry.theta(), 3.0 + 0.25 * (2 * M_PI - 6.0), 1e-12);
  EXPECT_NEAR(std::abs(log.scans[1].odometry.theta()), M_PI, 1e-6);
}

TEST_F(CarmenReader, WithoutOdomRecordsUsesTheScanFields) {
  const CarmenLog log = ReadCarmenLog(
      Write("FLASER 2 1 2 5 6 0.1 7 8 0.2 10.5 host 0\nFLASER 2 1 2 5 6 0.1 7 9 0.2 11 host 0\n"));
  ASSERT_EQ(log.scans.size(), 2u);
  ExpectSamePose(log.scans[0].odometry, Pose2(7, 8, 0.2));
  ExpectSamePose(log.scans[0].logged_pose, Pose2(5, 6, 0.1));
  ExpectSamePose(log.scans[1].odometry, Pose2(7, 9, 0.2));
  EXPECT_TRUE(log.odometry.empty());
}

TEST_F(CarmenReader, FrontLaserGeometryFromParams) {
  const std::string params =
      "PARAM laser_front_laser_fov 100 host 0\nPARAM laser_front_laser_max_range 8 host 0\n"
      "PARAM robot_front_laser_max 50 host 0\nPARAM robot_frontlaser_offset 0.25 host 0\n";
  const CarmenLog log = ReadCarmenLog(
      Write(params + "FLASER 5 1 2 3 8 7 0 0 0 0 0 0 1 host 0\n"  // odd: both ends included
                     "FLASER 4 1 2 3 4 0 0 0 0 0 0 2 host 0\n"));  // even: fov / n
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_DOUBLE_EQ(log.scans[0].angle_min_rad, DegToRad(-50.0));
  EXPECT_DOUBLE_EQ(log.scans[0].angle_increment_rad, DegToRad(25.0));
  EXPECT_DOUBLE_EQ(log.scans[0].BeamAngle(4), DegToRad(50.0));
  EXPECT_DOUBLE_EQ(log.scans[1].angle_increment_rad, DegToRad(25.0));
  EXPECT_EQ(log.scans[0].max_range_m, 8.0);
  EXPECT_FALSE(log.scans[0].IsReturn(3));  // 8 m: at the PARAM's range
  EXPECT_TRUE(log.scans[0].IsReturn(4));   // 7 m
  EXPECT_TRUE(log.notes.empty());
  ExpectSamePose(log.scans[0].laser_offset, Pose2(0.25, 0, 0));
  EXPECT_EQ(log.params.at("laser_front_laser_fov"), "100");

  const CarmenLog plain = ReadCarmenLog(Write("FLASER 4 1 2 3 4 0 0 0 0 0 0 2 host 0\n"));
  EXPECT_DOUBLE_EQ(plain.scans[0].angle_increment_rad, M_PI / 4.0);
  EXPECT_EQ(plain.scans[0].max_range_m, 4.0);  // no PARAM: the largest reading
}

// Without a PARAM, the no-return range is the largest reading over all the log's scans: the
// beams at it are no-returns, every shorter one is a return.
TEST_F(CarmenReader, MaxRangeWithoutParamIsTheLargestReading) {
  const CarmenLog log = ReadCarmenLog(Write("FLASER 3 1 2 3 0 0 0 0 0 0 1 host 0\n"
                                            "FLASER 3 1 40.5 2 0 0 0 0 0 0 2 host 0\n"
                                            "FLASER 3 40.5 7 0 0 0 0 0 0 0 3 host 0\n"));
  ASSERT_EQ(log.scans.size(), 3u);
  for (const LaserScan& scan : log.scans) EXPECT_EQ(scan.max_range_m, double(40.5f));
  EXPECT_TRUE(log.scans[0].IsReturn(2));    // 3 m
  EXPECT_FALSE(log.scans[1].IsReturn(1));   // 40.5 m: the no-return value
  EXPECT_TRUE(log.scans[2].IsReturn(1));    // 7 m
  EXPECT_FALSE(log.scans[2].IsReturn(2));   // 0: never a return
}

// A PARAM gives the range of the scans after it; scans before it take the largest reading of the
// scans that no PARAM covers; ROBOTLASER1 records carry their own.
TEST_F(CarmenReader, MaxRangeFromParamCoversTheScansAfterIt) {
  const CarmenLog log = ReadCarmenLog(
      Write("FLASER 2 1 30 0 0 0 0 0 0 1 host 0\n"
            "PARAM robot_front_laser_max 20 host 0\n"
            "FLASER 2 1 20 0 0 0 0 0 0 2 host 0\n"
            "ROBOTLASER1 0 -1.5 3.0 0.01 12 0.01 0 2 1.0 2.0 0 0 0 0 0 0 0 0 0 0 0 0 3 host 3\n"));
  ASSERT_EQ(log.scans.size(), 3u);
  EXPECT_EQ(log.scans[0].max_range_m, 30.0);  // the uncovered scans' largest reading
  EXPECT_EQ(log.scans[1].max_range_m, 20.0);
  EXPECT_FALSE(log.scans[1].IsReturn(1));
  EXPECT_EQ(log.scans[2].max_range_m, 12.0);
}

// Issue 9: edmonton's `PARAM robot_front_laser_max 10` sits under a third of its readings (up to
// 51 m). Trusted, it turned every return beyond 10 m into a no-return (free space through the
// wall up to the usable range), and the map of its open halls broke (ATE 1.0-6.4 m over seeds
// 1-5 against 0.2-0.7 m with the readings' range). A PARAM the readings contradict is dropped.
TEST_F(CarmenReader, AParamMaxRangeTheReadingsContradictIsDropped) {
  std::string text = "PARAM robot_front_laser_max 10 host 0\n";
  for (int k = 0; k < 5; ++k) {
    text += fmt::format("FLASER 4 2 9.5 14.25 51.15 0 0 0 0 0 0 {} host {}\n", k + 1, k + 1);
  }
  const CarmenLog log = ReadCarmenLog(Write(text));
  ASSERT_EQ(log.scans.size(), 5u);
  for (const LaserScan& scan : log.scans) EXPECT_EQ(scan.max_range_m, double(51.15f));
  EXPECT_TRUE(log.scans[0].IsReturn(2));   // 14.25 m: a wall, not a no-return
  EXPECT_FALSE(log.scans[0].IsReturn(3));  // 51.15 m: the laser's no-return value
  EXPECT_EQ(log.no_return_beams, 5);
  ASSERT_EQ(log.notes.size(), 1u);
  EXPECT_NE(log.notes[0].find("10 of 20 readings of its 5 scans lie above it"), std::string::npos)
      << log.notes[0];
  // Readings at the PARAM (its no-return value) or a rounding above it do not contradict it.
  const CarmenLog kept = ReadCarmenLog(Write("PARAM robot_front_laser_max 10 host 0\n"
                                             "FLASER 3 2 10.005 10 0 0 0 0 0 0 1 host 0\n"));
  EXPECT_EQ(kept.scans[0].max_range_m, 10.0);
  EXPECT_TRUE(kept.notes.empty());
  EXPECT_EQ(kept.no_return_beams, 2);
}

// Issue 8 item 5: a "log" without line ends (/dev/zero) grew the line buffer until memory ran
// out; a line beyond 64 MiB is an input error.
TEST_F(CarmenReader, ALineLongerThan64MiBIsAnInputError) {
  const std::string message = testing::InputErrorOf([] { ReadCarmenLog("/dev/zero"); });
  EXPECT_NE(message.find("/dev/zero:1: a line longer than 64 MiB"), std::string::npos) << message;
}

TEST_F(CarmenReader, MaxRangeOptionOverridesTheLog) {
  CarmenReadOptions options;
  options.max_range_m = 25.0;
  const CarmenLog log = ReadCarmenLog(
      Write("FLASER 2 1 30 0 0 0 0 0 0 1 host 0\n"
            "PARAM laser_front_laser_max_range 20 host 0\n"
            "FLASER 2 1 24 0 0 0 0 0 0 2 host 0\n"
            "ROBOTLASER1 0 -1.5 3.0 0.01 12 0.01 0 2 1.0 2.0 0 "
            "0 0 0 0 0 0 0 0 0 0 0 3 host 3\n"),
      options);
  ASSERT_EQ(log.scans.size(), 3u);
  for (const LaserScan& scan : log.scans) EXPECT_EQ(scan.max_range_m, 25.0);
  EXPECT_TRUE(log.scans[1].IsReturn(1));  // 24 m: a return under the user's range
}

TEST_F(CarmenReader, ReadsRobotLaser1) {
  // The laser sits at (0.2, 0.1, 0.05) in the robot frame; the robot is at (2, 3, 0.5).
  const CarmenLog log = ReadCarmenLog(
      Write("ROBOTLASER1 0 -1.5 3.0 0.01 30 0.01 0 3 1.0 2.0 40 2 7 8 "
            "2.127573959 3.183643364 0.55 2 3 0.5 0.3 0.1 0.5 0.2 0 42.5 host 42.6\n"));
  ASSERT_EQ(log.scans.size(), 1u);
  const LaserScan& scan = log.scans[0];
  EXPECT_EQ(scan.angle_min_rad, -1.5);
  EXPECT_EQ(scan.angle_increment_rad, 0.01);
  EXPECT_EQ(scan.max_range_m, 30.0);
  EXPECT_EQ(scan.ranges_m, (std::vector<float>{1.0f, 2.0f, 40.0f}));
  EXPECT_FALSE(scan.IsReturn(2));
  EXPECT_EQ(scan.t_s, 42.5);
  ExpectSamePose(scan.logged_pose, Pose2(2, 3, 0.5));
  ExpectSamePose(scan.odometry, Pose2(2, 3, 0.5));
  EXPECT_TRUE(scan.laser_offset.vector().isApprox(Eigen::Vector3d(0.2, 0.1, 0.05), 1e-8));
}

TEST_F(CarmenReader, IgnoresCommentsBlankLinesAndOtherRecords) {
  const CarmenLog log = ReadCarmenLog(Write("# header\r\n\r\nNEFF 11.6 0 pippo 0\r\n"
                                            "TRUEPOS 1 2 3 4 5 6 7 h 0\r\n" +
                                            Odom(1, 2, 0.3, 5) + "   \n" + Flaser(5)));
  EXPECT_EQ(log.scans.size(), 1u);
  EXPECT_EQ(log.odometry.size(), 1u);
  EXPECT_TRUE(Contains(ErrorOfLog("# a\n\nNEFF x\nFLASER 2 1\n"), "log.clf:4: FLASER field 'n'"));
}

}  // namespace
}  // namespace slamkit
