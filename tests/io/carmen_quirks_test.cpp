// Issue 9: logs written by other SLAM programs, read without skip_bad_lines. Each test writes
// one synthetic log with one quirk and checks the poses (or the error) it gives.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>
#include <vector>

#include "slamkit/io/carmen_reader.hpp"

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"
#include "common/pose_expect.hpp"

namespace slamkit {
namespace {

using testing::Contains;

// `{}` prints the shortest text that reads back as the same double, so poses compare exactly.
std::string Odom(const Pose2& p, const std::string& t) {
  return fmt::format("ODOM {} {} {} 0 0 0 {} host 0\n", p.x(), p.y(), p.theta(), t);
}
// The copy of the corrected pose that GMapping-like programs write after every scan.
std::string GmappingCopy(const Pose2& p, const std::string& t = "0") {
  return fmt::format("ODOM {} {} {} 0 0 0 {} pippo 0\n", p.x(), p.y(), p.theta(), t);
}
std::string Flaser(const Pose2& logged, const Pose2& odom, const std::string& t) {
  return fmt::format("FLASER 3 1.5 2.5 4 {} {} {} {} {} {} {} host 0\n", logged.x(), logged.y(),
                     logged.theta(), odom.x(), odom.y(), odom.theta(), t);
}

using testing::ExpectSamePose;
// The pose a fraction s of the way from a to b (the headings here are far from the ±π wrap).
Pose2 Between(const Pose2& a, const Pose2& b, double s) {
  return Pose2(a.vector() + s * (b.vector() - a.vector()));
}
void ExpectNearPose(const Pose2& actual, const Pose2& expected) {
  EXPECT_TRUE(actual.vector().allFinite());
  EXPECT_TRUE(actual.vector().isApprox(expected.vector(), 1e-12))
      << actual.vector().transpose() << " vs " << expected.vector().transpose();
}
::testing::AssertionResult HasNote(const CarmenLog& log, const std::string& part) {
  std::string notes;
  for (const std::string& note : log.notes) {
    if (note.find(part) != std::string::npos) return ::testing::AssertionSuccess();
    notes += " '" + note + "'";
  }
  return ::testing::AssertionFailure() << "no note has '" << part << "'; notes:" << notes;
}

class CarmenQuirks : public testing::TempDirTest {
 protected:
  CarmenLog Read(const std::string& text, bool interpolate = false) const {
    CarmenReadOptions options;
    options.odometry_from_scan_fields = !interpolate;
    return ReadCarmenLog(WriteFile("log.clf", text), options);
  }
  std::string ErrorOf(const std::string& text) const {
    return testing::InputErrorOf([&] { ReadCarmenLog(WriteFile("log.clf", text)); });
  }
};

// Odometry records a (t = 1) and b (t = 2); three scans at 0.5, 1.5 and 2, each followed by a
// copy of its corrected pose stamped 0 or with a denormal.
const Pose2 kOdomA(0, 0, 0), kOdomB(1, 0.5, 0.25);
const std::vector<Pose2> kCorrected = {Pose2(5, 6, 0.5), Pose2(5.5, 6, 0.6), Pose2(6, 6.5, 0.7)};
const std::vector<Pose2> kScanFields = {Pose2(-0.1, 0, 0), Pose2(0.5, 0.2, 0.1), kOdomB};

std::string GmappingLog() {
  return Flaser(kCorrected[0], kScanFields[0], "0.5") + GmappingCopy(kCorrected[0]) +
         Odom(kOdomA, "1") + Flaser(kCorrected[1], kScanFields[1], "1.5") +
         GmappingCopy(kCorrected[1], "1.08499e-42") + Odom(kOdomB, "2") +
         Flaser(kCorrected[2], kScanFields[2], "2") + GmappingCopy(kCorrected[2]);
}

TEST_F(CarmenQuirks, GmappingStampZeroCopiesLeaveTheScanFieldsByDefault) {
  const CarmenLog log = Read(GmappingLog());
  ASSERT_EQ(log.scans.size(), 3u);
  ASSERT_EQ(log.odometry.size(), 5u);  // the copies are kept as records, in log order
  EXPECT_EQ(log.odometry[0].t_s, 0.0);
  ExpectSamePose(log.odometry[0].pose, kCorrected[0]);
  for (std::size_t k = 0; k < 3; ++k) {
    ExpectSamePose(log.scans[k].odometry, kScanFields[k]);
    ExpectSamePose(log.scans[k].logged_pose, kCorrected[k]);
  }
  EXPECT_EQ(log.time_steps_back, 0);
  EXPECT_TRUE(log.notes.empty());
}

// Sorted by time, the copies came first: the scan before the first stamped record took the last
// copy's pose. Without a timestamp a record cannot be placed in time, so it is not used.
TEST_F(CarmenQuirks, GmappingStampZeroCopiesAreNotInterpolated) {
  const CarmenLog log = Read(GmappingLog(), /*interpolate=*/true);
  ASSERT_EQ(log.scans.size(), 3u);
  ExpectSamePose(log.scans[0].odometry, kOdomA);  // before the first stamped record
  ExpectNearPose(log.scans[1].odometry, Between(kOdomA, kOdomB, 0.5));
  ExpectSamePose(log.scans[2].odometry, kOdomB);
  EXPECT_TRUE(HasNote(log, "3 of 5 ODOM records have no timestamp"));
}

TEST_F(CarmenQuirks, OnlyUnstampedOdomRecordsFallBackToTheScanFields) {
  const CarmenLog log = Read(Flaser(kCorrected[0], kScanFields[0], "0.5") +
                                 GmappingCopy(kCorrected[0]) +
                                 Flaser(kCorrected[1], kScanFields[1], "1.5") +
                                 GmappingCopy(kCorrected[1], "1.08499e-42"),
                             /*interpolate=*/true);
  ASSERT_EQ(log.scans.size(), 2u);
  ExpectSamePose(log.scans[0].odometry, kScanFields[0]);
  ExpectSamePose(log.scans[1].odometry, kScanFields[1]);
  ASSERT_EQ(log.notes.size(), 1u);
  EXPECT_TRUE(Contains(log.notes[0], "none of the 2 ODOM records has a timestamp, so the "
                                     "odometry comes from the scan records' own fields"));
}

// Every record stamped 0: no order to check, scans in log order, odometry from the scan fields.
TEST_F(CarmenQuirks, LogWithoutTimestampsIsReadInLogOrder) {
  std::string text;
  std::vector<Pose2> fields;
  for (int k = 0; k < 4; ++k) {
    fields.push_back(Pose2(0.5 * k, 4.0 - k, 0.1 * k));
    text += Odom(Pose2(10.0 + k, 0, 0), "0") + Flaser(Pose2(k, 0, 0), fields.back(), "0");
  }
  for (const bool interpolate : {false, true}) {
    const CarmenLog log = Read(text, interpolate);
    ASSERT_EQ(log.scans.size(), 4u);
    EXPECT_EQ(log.odometry.size(), 4u);
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_EQ(log.scans[k].t_s, 0.0);
      ExpectSamePose(log.scans[k].logged_pose, Pose2(double(k), 0, 0));  // log order
      ExpectSamePose(log.scans[k].odometry, fields[k]);
    }
    EXPECT_EQ(log.time_steps_back, 0);
    EXPECT_EQ(log.skipped_lines, 0);
    if (interpolate) {
      EXPECT_TRUE(HasNote(log, "none of the 4 ODOM records has a timestamp"));
    } else {
      EXPECT_TRUE(log.notes.empty());
    }
  }
}

// Stamped ODOM records but scans without a timestamp: those scans keep their own fields.
TEST_F(CarmenQuirks, UnstampedScansKeepTheirFieldsWhenInterpolating) {
  const CarmenLog log = Read(Odom(kOdomA, "1") + Flaser(kCorrected[0], kScanFields[0], "0") +
                                 Odom(kOdomB, "2") + Flaser(kCorrected[1], kScanFields[1], "1.5"),
                             /*interpolate=*/true);
  ASSERT_EQ(log.scans.size(), 2u);
  ExpectSamePose(log.scans[0].odometry, kScanFields[0]);
  ExpectNearPose(log.scans[1].odometry, Between(kOdomA, kOdomB, 0.5));
  EXPECT_TRUE(HasNote(log, "1 of 2 scans have no timestamp"));
}

// Repeated scan and ODOM stamps are in order; interpolation never divides by the zero interval
// between records that share a stamp: at that stamp the last of them in the log is the pose.
TEST_F(CarmenQuirks, DuplicatedTimestampsAreReadAndInterpolatedWithoutNaN) {
  const Pose2 a(0, 0, 0), b(0.2, 0, 0), c(1, 0.1, 0.05), d(1.5, 0.2, 0.1), e(3, 0.4, 0.3),
      f(3.5, 0.4, 0.35);
  const Pose2 field(9, 8, 0.7);
  const std::string text = Odom(a, "1") + Odom(b, "1") + Flaser(field, field, "1") +
                           Odom(c, "2") + Odom(d, "2") + Flaser(field, field, "1.5") +
                           Flaser(field, field, "2") + Flaser(field, field, "2") +
                           Odom(e, "3") + Odom(f, "3") + Flaser(field, field, "2.5") +
                           Flaser(field, field, "3");
  const CarmenLog fields = Read(text);
  ASSERT_EQ(fields.scans.size(), 6u);
  for (const LaserScan& scan : fields.scans) ExpectSamePose(scan.odometry, field);
  EXPECT_EQ(fields.time_steps_back, 0);

  const CarmenLog log = Read(text, /*interpolate=*/true);
  ASSERT_EQ(log.scans.size(), 6u);
  EXPECT_EQ(log.scans[2].t_s, log.scans[3].t_s);
  ExpectSamePose(log.scans[0].odometry, b);  // at the first, shared stamp: the last record
  ExpectNearPose(log.scans[1].odometry, Between(b, c, 0.5));  // the last at 1, the first at 2
  ExpectSamePose(log.scans[2].odometry, d);  // exactly at a shared stamp inside the span
  ExpectSamePose(log.scans[3].odometry, d);
  ExpectNearPose(log.scans[4].odometry, Between(d, e, 0.5));
  ExpectSamePose(log.scans[5].odometry, f);  // at the last, shared stamp
  EXPECT_EQ(log.time_steps_back, 0);
  EXPECT_EQ(log.skipped_lines, 0);
  EXPECT_TRUE(log.notes.empty());
}

// Records without a timestamp do not reset a stream's clock: a step back beyond
// max_time_step_back_s across them is still an error naming the line of the earlier stamp.
TEST_F(CarmenQuirks, TimeGoingBackAcrossUnstampedRecordsIsAnError) {
  EXPECT_TRUE(Contains(ErrorOf(Odom(kOdomA, "10") + GmappingCopy(kOdomA) + Odom(kOdomB, "5")),
                       "log.clf:3: ODOM field 'timestamp': time goes backwards (5.000000 < "
                       "10.000000 on line 1)"));
  EXPECT_TRUE(Contains(ErrorOf(Flaser(kOdomA, kOdomA, "10") + Flaser(kOdomA, kOdomA, "0") +
                               Flaser(kOdomA, kOdomA, "1e-300") + Flaser(kOdomA, kOdomA, "8.5")),
                       "log.clf:4: FLASER field 'timestamp': time goes backwards (8.500000 < "
                       "10.000000 on line 1)"));
}

}  // namespace
}  // namespace slamkit
