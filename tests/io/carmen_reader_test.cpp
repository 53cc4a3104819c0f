#include "slamkit/io/carmen_reader.hpp"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <limits>
#include <zlib.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/error.hpp"

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"
#include "common/pose_expect.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;
using testing::Contains;
using testing::ReadText;

const fs::path kCarmenDir = fs::path(SLAMKIT_DATASETS_DIR) / "carmen";

std::string Odom(double x, double y, double theta, double t) {
  return "ODOM " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(theta) +
         " 0 0 0 " + std::to_string(t) + " host 0\n";
}
// Three beams; the pose fields say (9, 8, 0.7) so that a test sees which odometry was used.
std::string Flaser(double t) {
  return "FLASER 3 1.5 2.5 81.83 9 8 0.7 9 8 0.7 " + std::to_string(t) + " host 0\n";
}

void WriteGzip(const fs::path& path, const std::string& text) {
  gzFile file = gzopen(path.c_str(), "wb");
  ASSERT_NE(file, nullptr);
  ASSERT_EQ(gzwrite(file, text.data(), static_cast<unsigned>(text.size())),
            static_cast<int>(text.size()));
  ASSERT_EQ(gzclose(file), Z_OK);
}

using testing::ExpectSamePose;

class CarmenReader : public testing::TempDirTest {
 protected:
  fs::path Write(const std::string& text, const std::string& name = "log.clf") const {
    return WriteFile(name, text);
  }
  std::string ErrorOf(const fs::path& path, const CarmenReadOptions& options = {}) const {
    return testing::InputErrorOf([&] { ReadCarmenLog(path, options); });
  }
  std::string ErrorOfLog(const std::string& text) const { return ErrorOf(Write(text)); }
};

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

TEST_F(CarmenReader, RejectsMalformedLinesWithTheirNumber) {
  const std::string ok = "# header\n" + Odom(0, 0, 0, 10) + Flaser(10);
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "FLASER 3 1 2 0 0 0 0 0 0 2 host 0\n"),
                       "log.clf:4: FLASER field 'n': 3 readings need 13 fields after FLASER, "
                       "got 12"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "FLASER 3 1 2 3 4 0 0 0 0 0 0 2 host 0\n"),
                       "log.clf:4: FLASER field 'n': 3 readings need 13 fields"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "FLASER 3 1 abc 3 0 0 0 0 0 0 2 host 0\n"),
                       "log.clf:4: FLASER field 'r2': not a number ('abc')"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "FLASER 3 1 2 3 nan 0 0 0 0 0 2 host 0\n"),
                       "log.clf:4: FLASER field 'x': not a finite number ('nan')"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "FLASER -3 1 2 3 0 0 0 0 0 0 2 host 0\n"),
                       "log.clf:4: FLASER field 'n': negative count ('-3')"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "ODOM 0 0 inf 0 0 0 2 host 0\n"),
                       "log.clf:4: ODOM field 'theta': not a finite number ('inf')"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "ODOM 0 0 0 0 0 0 2 host\n"),
                       "log.clf:4: ODOM field 'logger_timestamp': missing"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + Odom(0, 0, 0, 5)),
                       "log.clf:4: ODOM field 'timestamp': time goes backwards (5.000000 < "
                       "10.000000 on line 2)"));
  EXPECT_TRUE(
      Contains(ErrorOfLog(ok + Flaser(8.5)), "log.clf:4: FLASER field 'timestamp': time goes"));
  // Clock jitter of up to max_time_step_back_s is accepted and counted.
  EXPECT_EQ(ReadCarmenLog(Write(ok + Flaser(9.5))).time_steps_back, 1);
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "ROBOTLASER1 0 -1.5 3 0.01 30 0.01 0 2 1 2 0 0 0 0 0 0 0\n"),
                       "log.clf:4: ROBOTLASER1 field 'num_readings': 2 readings and 0 remissions "
                       "need 25 fields after ROBOTLASER1, got 17"));
  // Streams are checked separately, and a step back within 1e-6 s is rounding.
  EXPECT_EQ(ReadCarmenLog(Write(Odom(0, 0, 0, 5) + Flaser(1) + Odom(0, 0, 0, 4.9999995)))
                .scans.size(),
            1u);
}

// Issue 8 item 9: values that make no physical sense are input errors naming line and field.
TEST_F(CarmenReader, RejectsValuesThatMakeNoPhysicalSense) {
  const std::string ok = Odom(0, 0, 0, 10) + Flaser(10);
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "FLASER 3 1 -2 3 0 0 0 0 0 0 11 host 0\n"),
                       "log.clf:3: FLASER field 'r2': negative range ('-2')"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "FLASER 0 0 0 0 0 0 0 11 host 0\n"),
                       "log.clf:3: FLASER field 'n': no readings"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "ROBOTLASER1 0 -1.5 3 0.01 30 0.01 0 0 0 "
                                       "0 0 0 0 0 0 0 0 0 0 0 11 host 0\n"),
                       "log.clf:3: ROBOTLASER1 field 'num_readings': no readings"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "ROBOTLASER1 0 -1.5 3 0.01 -5 0.01 0 1 1 0 "
                                       "0 0 0 0 0 0 0 0 0 0 0 11 host 0\n"),
                       "log.clf:3: ROBOTLASER1 field 'max_range': max range must be positive"));
  for (const char* fov : {"-180", "0", "1e300", "361"}) {
    EXPECT_TRUE(Contains(ErrorOfLog(std::string("PARAM laser_front_laser_fov ") + fov +
                                    " host 0\n" + ok),
                         "log.clf:1: PARAM field 'value': laser_front_laser_fov must be in (0, "
                         "360]"))
        << fov;
  }
  for (const char* name : {"laser_front_laser_max_range", "robot_front_laser_max"}) {
    for (const char* range : {"-5", "0"}) {
      EXPECT_TRUE(Contains(ErrorOfLog(std::string("PARAM ") + name + " " + range + " host 0\n" +
                                      ok),
                           "log.clf:1: PARAM field 'value': max range must be positive"))
          << name << " " << range;
    }
  }
  EXPECT_TRUE(Contains(ErrorOfLog("PARAM robot_frontlaser_offset 1e300 host 0\n" + ok),
                       "log.clf:1: PARAM field 'value': magnitude above 1e+06"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "FLASER 3 1 2 3 1e308 0 0 0 0 0 11 host 0\n"),
                       "log.clf:3: FLASER field 'x': magnitude above 1e+06 ('1e308')"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "FLASER 3 1 2 3 0 0 0 0 0 -1e308 11 host 0\n"),
                       "log.clf:3: FLASER field 'odom_theta': magnitude above"));
  EXPECT_TRUE(Contains(ErrorOfLog(ok + "ODOM 0 1e308 0 0 0 0 11 host 0\n"),
                       "log.clf:3: ODOM field 'y': magnitude above"));
  // The bounds themselves and a 2π radian field of view are fine.
  EXPECT_EQ(ReadCarmenLog(Write("PARAM laser_front_laser_fov 6.283185307179586 host 0\n"
                                "PARAM robot_front_laser_max 1e6 host 0\n"
                                "FLASER 3 0 2 3 1e6 -1e6 0 0 0 0 11 host 0\n"))
                .scans.size(),
            1u);
}

// Found by fuzz/carmen_fuzzer.cpp's check that poses and beam angles are finite: timestamps near
// ±1e308 overflowed the odometry interpolation into a NaN pose (inf / inf), and ROBOTLASER1
// angles near 1e308 made the later beams' angles infinite. Both are now bounded when read.
TEST_F(CarmenReader, RejectsTimestampsAndAnglesThatWouldOverflow) {
  CarmenReadOptions interpolate;
  interpolate.odometry_from_scan_fields = false;
  EXPECT_TRUE(Contains(ErrorOf(Write("ODOM 0 0 0 0 0 0 -1.7e308 host 0\n"
                                     "FLASER 1 1 0 0 0 0 0 0 1.7e308 host 0\n"
                                     "ODOM 1 0 0 0 0 0 1.75e308 host 0\n"),
                               interpolate),
                       "log.clf:1: ODOM field 'timestamp': magnitude above 1e+12 s ('-1.7e308')"));
  EXPECT_TRUE(Contains(ErrorOfLog("FLASER 1 1 0 0 0 0 0 0 1.7e308 host 0\n"),
                       "log.clf:1: FLASER field 'timestamp': magnitude above 1e+12 s"));
  const std::string tail = " 0 0 0 0 0 0 0 0 0 0 0 43 host 43\n";
  EXPECT_TRUE(Contains(ErrorOfLog("ROBOTLASER1 0 -1.5 3.0 0.01 30 0.01 0 2 1.0 2.0 0 0 0 0 0 0 0 0 "
                                  "0 0 0 0 1e13 host 43\n"),
                       "log.clf:1: ROBOTLASER1 field 'timestamp': magnitude above 1e+12 s"));
  EXPECT_TRUE(Contains(ErrorOfLog("ROBOTLASER1 0 1e308 3.0 0.01 30 0.01 0 2 1.0 2.0 0" + tail),
                       "log.clf:1: ROBOTLASER1 field 'start_angle': magnitude above 1e+06"));
  EXPECT_TRUE(Contains(ErrorOfLog("ROBOTLASER1 0 0 3.0 -1e308 30 0.01 0 2 1.0 2.0 0" + tail),
                       "log.clf:1: ROBOTLASER1 field 'angular_resolution': magnitude above"));
  // The bounds themselves are fine.
  const CarmenLog log = ReadCarmenLog(
      Write("ODOM 0 0 0 0 0 0 -1e12 host 0\nFLASER 1 1 0 0 0 0 0 0 1e12 host 0\n"
            "ROBOTLASER1 0 -1e6 3.0 1e6 30 0.01 0 2 1.0 2.0 0 0 0 0 0 0 0 0 0 0 0 0 1e12 host 0\n"),
      interpolate);
  ASSERT_EQ(log.scans.size(), 2u);
  EXPECT_TRUE(log.scans[0].odometry.vector().allFinite());
  EXPECT_EQ(log.scans[1].BeamAngle(1), 0.0);
}

// Issue 8 item 11: a log with nothing to process says what was expected.
TEST_F(CarmenReader, RejectsLogsWithoutScans) {
  for (const std::string& text : {std::string(""), std::string("# only a comment\n\n"),
                                 Odom(0, 0, 0, 1) + Odom(1, 0, 0, 2),
                                 std::string("\x7f" "ELF\x02\x01\x01\0\0\0", 10)}) {
    EXPECT_TRUE(Contains(ErrorOfLog(text),
                         "log.clf: no laser scans (expected a CARMEN log with FLASER or "
                         "ROBOTLASER1 records)"));
  }
  EXPECT_TRUE(Contains(ErrorOfLog("#ROSBAG V2.0\nE\0\0\0"),
                       "log.clf:1: a ROS bag (#ROSBAG header), expected a CARMEN log"));
}

TEST_F(CarmenReader, SkipsAndCountsBadLines) {
  const std::string text = Odom(0, 0, 0, 1) + "FLASER 3 1 2 0 0 0 0 0 0 2 host 0\n" + Flaser(1) +
                           "FLASER 3 1 abc 3 0 0 0 0 0 0 2 host 0\n" + Odom(std::nan(""), 0, 0, 2) +
                           Odom(2, 0, 0, 3) + Odom(0, 0, 0, 0.5) + Flaser(3);
  CarmenReadOptions options;
  options.skip_bad_lines = true;
  options.odometry_from_scan_fields = false;
  const CarmenLog log = ReadCarmenLog(Write(text), options);
  EXPECT_EQ(log.skipped_lines, 4);
  EXPECT_EQ(log.scans.size(), 2u);
  ASSERT_EQ(log.odometry.size(), 2u);
  EXPECT_EQ(log.odometry[1].t_s, 3.0);
  ExpectSamePose(log.scans[0].odometry, Pose2(0, 0, 0));
  ExpectSamePose(log.scans[1].odometry, Pose2(2, 0, 0));
}

TEST_F(CarmenReader, ReadsGzipLikePlain) {
  std::string text = "PARAM robot_frontlaser_offset 0.1 host 0\n";
  for (int i = 0; i < 50; ++i) text += Odom(0.1 * i, 0.01 * i, 0.02 * i, i) + Flaser(i + 0.3);
  const CarmenLog plain = ReadCarmenLog(Write(text));
  const fs::path gz = dir_ / "log.clf";  // gzip is recognised by content, not by name
  WriteGzip(gz, text);
  ASSERT_NE(ReadText(gz), text);
  const CarmenLog packed = ReadCarmenLog(gz);
  ASSERT_EQ(packed.scans.size(), 50u);
  ASSERT_EQ(packed.scans.size(), plain.scans.size());
  ASSERT_EQ(packed.odometry.size(), plain.odometry.size());
  EXPECT_EQ(packed.params, plain.params);
  for (std::size_t k = 0; k < plain.scans.size(); ++k) {
    EXPECT_EQ(packed.scans[k].t_s, plain.scans[k].t_s);
    EXPECT_EQ(packed.scans[k].ranges_m, plain.scans[k].ranges_m);
    ExpectSamePose(packed.scans[k].odometry, plain.scans[k].odometry);
    ExpectSamePose(packed.scans[k].laser_offset, Pose2(0.1, 0, 0));
  }
}

TEST_F(CarmenReader, TruncatedGzipAndMissingFileNameTheFile) {
  std::string text;
  for (int i = 0; i < 2000; ++i) text += Odom(0.1 * i, 0.01 * i, 0.02 * i, i) + Flaser(i + 0.3);
  const fs::path gz = dir_ / "whole.clf.gz";
  WriteGzip(gz, text);
  const std::string bytes = ReadText(gz);
  ASSERT_GT(bytes.size(), 1000u);
  EXPECT_EQ(ReadCarmenLog(gz).scans.size(), 2000u);
  const fs::path cut = Write(bytes.substr(0, bytes.size() / 2), "cut.clf.gz");
  EXPECT_TRUE(Contains(ErrorOf(cut), "cut.clf.gz: truncated gzip file"));
  const fs::path tail = Write(bytes.substr(0, bytes.size() - 4), "tail.clf.gz");  // no length
  EXPECT_TRUE(Contains(ErrorOf(tail), "tail.clf.gz"));
  EXPECT_TRUE(Contains(ErrorOf(dir_ / "absent.clf"), "absent.clf: cannot open file"));
}

}  // namespace
}  // namespace slamkit
