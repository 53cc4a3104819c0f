// End-to-end runs on the real data sets in ../shared/datasets (read in place, never copied).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit {
namespace {

using testing::FreshDir;
using testing::ReadText;
using testing::RunCli;
namespace fs = std::filesystem;

const std::string kVictoria =
    std::string(SLAMKIT_DATASETS_DIR) + "/victoria_park/victoria_park_isam.txt";

TEST(VictoriaPark, KnownAssociationMapsEveryFileLandmark) {
  if (!fs::exists(kVictoria)) GTEST_SKIP() << "no " << kVictoria;
  const fs::path dir = FreshDir("victoria_known");
  const auto r = RunCli("run --isam " + kVictoria + " --known-association --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto m = nlohmann::json::parse(ReadText(dir / "metrics.json"));
  EXPECT_EQ(m["sightings"], 3640);
  EXPECT_DOUBLE_EQ(m["association_agreement"].get<double>(), 1.0);
  EXPECT_TRUE(fs::exists(dir / "estimate.tum"));
  EXPECT_TRUE(fs::exists(dir / "map.png"));
}

TEST(Intel, GridSlamOnTheFirstScansWritesTheContractFiles) {
  const std::string carmen = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/";
  if (!fs::exists(carmen + "intel.clf")) GTEST_SKIP() << "no intel.clf";
  const fs::path dir = FreshDir("intel_grid");
  const auto r = RunCli("grid --log " + carmen + "intel.clf --relations " + carmen +
                        "intel.relations --max-scans 600 --particles 8 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto m = nlohmann::json::parse(ReadText(dir / "metrics.json"));
  EXPECT_EQ(m["scans"], 600);
  EXPECT_GT(m["updates"].get<int>(), 5);
  EXPECT_GT(m["relations"].get<int>(), 10);
  // The start of the Intel log is an easy stretch: a working filter stays within decimetres.
  EXPECT_LT(m["relations_trans_mean_m"].get<double>(), 0.1);
  EXPECT_LT(m["relations_rot_mean_deg"].get<double>(), 3.0);
  for (const char* key : {"wall_time_s", "scans_per_s", "peak_rss_mib", "relations_trans_std_m",
                          "relations_rot_std_deg"}) {
    EXPECT_TRUE(m.contains(key)) << key;
  }
  const std::string trajectory = ReadText(dir / "trajectory.txt");
  EXPECT_EQ(std::count(trajectory.begin(), trajectory.end(), '\n'), 600);
  for (const char* file : {"trajectory.tum", "map.pgm", "map.yaml", "map.png"}) {
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  }
}

// The relations' rotational error on Intel comes mostly from scans between updates; tracking them
// against the map (the default) must cut it well below carrying them by odometry (measured on
// these scans: 0.46° against 1.62°).
TEST(Intel, TrackingBetweenUpdatesCutsTheRotationError) {
  const std::string carmen = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/";
  if (!fs::exists(carmen + "intel.clf")) GTEST_SKIP() << "no intel.clf";
  auto rotation_error = [&](const std::string& flags) {
    const fs::path dir = FreshDir("intel_tracking");
    const auto r = RunCli("grid --log " + carmen + "intel.clf --relations " + carmen +
                          "intel.relations --max-scans 3000 --particles 10 " + flags +
                          " --out " + dir.string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return nlohmann::json::parse(ReadText(dir / "metrics.json"))["relations_rot_mean_deg"]
        .get<double>();
  };
  const double tracked = rotation_error("");
  const double odometry = rotation_error("--no-tracking");
  EXPECT_LT(tracked, 0.5 * odometry) << tracked << "° tracked, " << odometry << "° odometry";
  EXPECT_LT(tracked, 0.8);
}

}  // namespace
}  // namespace slamkit
