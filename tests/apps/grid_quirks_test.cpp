// Issue 9: `slamkit grid` reads logs written by other SLAM programs without --skip-bad-lines.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "common/synthetic_room.hpp"

namespace slamkit {
namespace {

using testing::FreshDir;
using testing::ReadText;
using testing::RunCli;
namespace fs = std::filesystem;

// A FLASER record of the synthetic room seen from `pose` (logged pose and odometry fields).
std::string RoomFlaser(const Pose2& pose, double t_s) {
  const LaserScan scan = testing::RoomScan(pose);
  std::string line = fmt::format("FLASER {}", scan.ranges_m.size());
  for (float r : scan.ranges_m) line += fmt::format(" {:.3f}", r);
  const std::string xyt = fmt::format("{} {} {}", pose.x(), pose.y(), pose.theta());
  return line + fmt::format(" {} {} {} host {}\n", xyt, xyt, t_s, t_s);
}

// A GMapping-written log: after every scan an `ODOM ... 0 pippo 0` copy of its pose; and two
// scans share a timestamp (so do the ODOM records 0.01 s before them).
std::string QuirkyLog(int scans) {
  std::string text;
  for (int k = 0; k < scans; ++k) {
    const Pose2 pose(0.1 * k, 0.05 * k, 0.02 * k);
    const double t_s = 100.0 + (k == 3 ? 2 : k);  // scans 2 and 3 share their stamp
    text += fmt::format("ODOM {} {} {} 0 0 0 {} host {}\n", pose.x(), pose.y(), pose.theta(),
                        t_s - 0.01, t_s - 0.01);
    text += RoomFlaser(pose, t_s);
    text += fmt::format("ODOM {} {} {} 0 0 0 0 pippo 0\n", pose.x(), pose.y(), pose.theta());
  }
  return text;
}

TEST(GridQuirks, GmappingLogWithARepeatedScanStampRunsWithoutSkippingLines) {
  const fs::path dir = FreshDir("grid_quirks");
  const int scans = 6;
  std::ofstream(dir / "gfs.log") << QuirkyLog(scans);
  for (const char* odometry : {"", " --interpolate-odometry"}) {
    const fs::path out = dir / (*odometry ? "interpolated" : "fields");
    // 0.1 m per scan: --linear-update 0.2 makes the filter update on this short drive.
    const auto r = RunCli(fmt::format("grid --log {} --particles 3 --threads 1 --linear-update "
                                      "0.2{} --out {}",
                                      (dir / "gfs.log").string(), odometry, out.string()));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto m = nlohmann::json::parse(ReadText(out / "metrics.json"));
    EXPECT_EQ(m["skipped_lines"], 0) << odometry;
    EXPECT_EQ(m["scans"], scans) << odometry;
    EXPECT_GT(m["updates"].get<int>(), 0) << odometry;
    const std::string trajectory = ReadText(out / "trajectory.txt");
    EXPECT_EQ(std::count(trajectory.begin(), trajectory.end(), '\n'), scans) << odometry;
    // The repeated stamp is pushed forward for TUM readers, with a warning.
    EXPECT_NE(r.output.find("pushed forward"), std::string::npos) << r.output;
    if (*odometry) {
      const std::string note = fmt::format("{} of {} ODOM records have no timestamp", scans,
                                           2 * scans);
      EXPECT_NE(r.output.find(note), std::string::npos) << r.output;
    }
  }
}

}  // namespace
}  // namespace slamkit
