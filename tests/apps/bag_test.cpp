// ROS 1 bags in (issue 31 part 3): a bag written by scripts/ros/carmen_to_bag.py (Debian's
// python3-rosbag) from the first 2,000 Intel scans and intel.clf itself give the same trajectory
// (the bag's float32 beam angles taken back to the multiples of π they round from); bad bags are
// refused with the file and the reason, exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "slamkit/core/angle.hpp"

namespace slamkit::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kCarmen = fs::path(SLAMKIT_DATASETS_DIR) / "carmen";

struct Row {
  double t, x, y, theta;
};

// trajectory.tum: `t x y z qx qy qz qw` per pose (comment lines skipped).
std::vector<Row> Rows(const fs::path& path) {
  std::ifstream in(path);
  std::vector<Row> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    Row r{};
    double z, qx, qy, qz, qw;
    fields >> r.t >> r.x >> r.y >> z >> qx >> qy >> qz >> qw;
    r.theta = 2.0 * std::atan2(qz, qw);
    rows.push_back(r);
  }
  return rows;
}

// The largest difference of two runs' paths, pose by pose (times, x, y and θ); infinity when
// they differ in length.
double PathDifference(const fs::path& a_file, const fs::path& b_file) {
  const std::vector<Row> a = Rows(a_file), b = Rows(b_file);
  if (a.empty() || a.size() != b.size()) return std::numeric_limits<double>::infinity();
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max({worst, std::abs(a[i].t - b[i].t), std::abs(a[i].x - b[i].x),
                      std::abs(a[i].y - b[i].y), std::abs(WrapAngle(a[i].theta - b[i].theta))});
  }
  return worst;
}

// Each test in its own folder (ctest runs the tests of one program in parallel processes).
class Bag : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kCarmen / "intel.clf")) GTEST_SKIP() << "no intel.clf";
    dir_ = FreshDir(std::string("bag_") +
                    ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  // intel.bag from the first `scans` scans of intel.clf; false when the script failed.
  bool WriteBag(int scans) {
    scans_ = scans;
    const std::string command =
        "/usr/bin/python3 " + std::string(SLAMKIT_SOURCE_DIR) + "/scripts/ros/carmen_to_bag.py " +
        (kCarmen / "intel.clf").string() + " " + BagPath() + " --max-scans " +
        std::to_string(scans) + " >/dev/null 2>&1";
    return std::system(command.c_str()) == 0;
  }
  std::string BagPath() const { return (dir_ / "intel.bag").string(); }
  // The bag's scans read from intel.clf itself.
  std::string LogInput() const {
    return "--log " + (kCarmen / "intel.clf").string() + " --max-scans " + std::to_string(scans_);
  }

  int scans_ = 0;

  fs::path dir_;
};

TEST_F(Bag, GivesTheTrajectoryOfTheLogItWasWrittenFrom) {
  ASSERT_TRUE(WriteBag(2000)) << "scripts/ros/carmen_to_bag.py failed";
  const std::string relations = " --relations " + (kCarmen / "intel.relations").string();
  const CliResult bag = RunCli("grid --bag " + BagPath() + relations + " --out " +
                               (dir_ / "from_bag").string());
  ASSERT_EQ(bag.exit_code, 0) << bag.output;
  const CliResult log =
      RunCli("grid " + LogInput() + relations + " --out " + (dir_ / "from_log").string());
  ASSERT_EQ(log.exit_code, 0) << log.output;
  EXPECT_EQ(Rows(dir_ / "from_bag" / "trajectory.tum").size(), 2000u);
  EXPECT_LE(PathDifference(dir_ / "from_bag" / "trajectory.tum",
                           dir_ / "from_log" / "trajectory.tum"), 1e-9);
  EXPECT_LE(PathDifference(dir_ / "from_bag" / "odometry.tum", dir_ / "from_log" / "odometry.tum"),
            1e-9);
  const auto metrics = [&](const char* run) {
    return nlohmann::json::parse(std::ifstream(dir_ / run / "metrics.json"));
  };
  EXPECT_EQ(metrics("from_bag")["log"], BagPath());
  // The path is a SLAM result, not the odometry: the relations error is the grid filter's.
  EXPECT_LT(metrics("from_bag")["relations_trans_mean_m"].get<double>(), 0.05);
}

// features, localize and the pose-graph back end take --bag through the same input path: the
// same path from the bag as from the log.
TEST_F(Bag, FeaturesLocalizeAndThePoseGraphReadItToo) {
  ASSERT_TRUE(WriteBag(300)) << "scripts/ros/carmen_to_bag.py failed";
  for (const std::string command : {"features", "grid --backend graph"}) {
    const fs::path from_bag = dir_ / "from_bag", from_log = dir_ / "from_log";
    const CliResult bag = RunCli(command + " --bag " + BagPath() + " --out " + from_bag.string());
    ASSERT_EQ(bag.exit_code, 0) << command << "\n" << bag.output;
    const CliResult log = RunCli(command + " " + LogInput() + " --out " + from_log.string());
    ASSERT_EQ(log.exit_code, 0) << command << "\n" << log.output;
    EXPECT_LE(PathDifference(from_bag / "trajectory.tum", from_log / "trajectory.tum"), 1e-9)
        << command;
    fs::remove_all(from_bag);
    fs::remove_all(from_log);
  }
  // localize on the map grid made from the bag.
  ASSERT_EQ(RunCli("grid --bag " + BagPath() + " --out " + (dir_ / "map").string()).exit_code, 0);
  const std::string localize = "localize --map " + (dir_ / "map" / "map.yaml").string() +
                               " --initial-pose 0,0,0 ";
  const CliResult bag = RunCli(localize + "--bag " + BagPath() + " --out " +
                               (dir_ / "loc_bag").string());
  ASSERT_EQ(bag.exit_code, 0) << bag.output;
  ASSERT_EQ(RunCli(localize + LogInput() + " --out " + (dir_ / "loc_log").string()).exit_code, 0);
  EXPECT_LE(
      PathDifference(dir_ / "loc_bag" / "trajectory.tum", dir_ / "loc_log" / "trajectory.tum"),
      1e-9);
}

TEST_F(Bag, TopicsAndFramesAreChecked) {
  ASSERT_TRUE(WriteBag(50)) << "scripts/ros/carmen_to_bag.py failed";
  const std::string out = " --out " + (dir_ / "refused").string();
  const CliResult wrong_type = RunCli("grid --bag " + BagPath() + " --scan-topic /odom" + out);
  EXPECT_EQ(wrong_type.exit_code, 2);
  EXPECT_NE(wrong_type.output.find("topic /odom holds nav_msgs/Odometry, not "
                                   "sensor_msgs/LaserScan"), std::string::npos)
      << wrong_type.output;
  const CliResult missing = RunCli("grid --bag " + BagPath() + " --odom-topic /wheel" + out);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("no topic /wheel (the bag has: "), std::string::npos)
      << missing.output;
  EXPECT_NE(missing.output.find("/scan (sensor_msgs/LaserScan)"), std::string::npos);
  const CliResult no_tf = RunCli("grid --bag " + BagPath() + " --tf" + out);
  EXPECT_EQ(no_tf.exit_code, 2);
  EXPECT_NE(no_tf.output.find("no odom -> base_link transform on /tf"), std::string::npos);
  const CliResult both = RunCli("grid --bag " + BagPath() + " --log " +
                                (kCarmen / "intel.clf").string() + out);
  EXPECT_EQ(both.exit_code, 2);
  const CliResult neither = RunCli("grid" + out);
  EXPECT_EQ(neither.exit_code, 2);
  EXPECT_NE(neither.output.find("exactly one of --log and --bag"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "refused"));
}

TEST_F(Bag, ATruncatedBagOrAnotherFileIsAnInputError) {
  ASSERT_TRUE(WriteBag(50)) << "scripts/ros/carmen_to_bag.py failed";
  const fs::path truncated = dir_ / "truncated.bag";
  {
    std::ifstream in(BagPath(), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  }
  for (const fs::path& bad : {truncated, kCarmen / "intel.relations"}) {
    const CliResult r = RunCli("grid --bag " + bad.string() + " --out " +
                               (dir_ / "refused").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    EXPECT_NE(r.output.find(bad.string() + ": "), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "refused"));
  }
}

}  // namespace
}  // namespace slamkit::testing
