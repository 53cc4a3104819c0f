#include "slamkit/io/carmen_reader.hpp"

#include <gtest/gtest.h>

#include <zlib.h>

#include <cmath>
#include <cstddef>
#include <filesystem>
#include <string>

#include "slamkit/io/error.hpp"

#include "carmen_log_fixture.hpp"
#include "common/pose_expect.hpp"

// The CARMEN reader's refusals: malformed, absurd, overflowing and truncated input named by file,
// line and field; the lines it skips and counts; gzip read like plain text.
namespace slamkit {
namespace {

namespace fs = std::filesystem;
using carmen_test::CarmenReader;
using carmen_test::Flaser;
using carmen_test::Odom;
using testing::Contains;
using testing::ExpectSamePose;
using testing::ReadText;

void WriteGzip(const fs::path& path, const std::string& text) {
  gzFile file = gzopen(path.c_str(), "wb");
  ASSERT_NE(file, nullptr);
  ASSERT_EQ(gzwrite(file, text.data(), static_cast<unsigned>(text.size())),
            static_cast<int>(text.size()));
  ASSERT_EQ(gzclose(file), Z_OK);
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
