// End-to-end runs on the real data sets in ../shared/datasets (read in place, never copied):
// Victoria Park and Intel. The suite of CARMEN logs is in dataset_suite_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

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

// Each associator the command names runs and is recorded; a name it does not know is an
// argument error.
TEST(VictoriaPark, TheAssociationIsChosenByName) {
  if (!fs::exists(kVictoria)) GTEST_SKIP() << "no " << kVictoria;
  for (const std::string name : {"nn", "ml", "gnn", "jcbb", "known"}) {
    const fs::path dir = FreshDir("victoria_" + name);
    const auto r = RunCli("run --isam " + kVictoria + " --association " + name +
                          " --no-figures --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto m = nlohmann::json::parse(ReadText(dir / "metrics.json"));
    EXPECT_EQ(m["association"], name);
    EXPECT_EQ(m["known_association"], name == "known");
    EXPECT_GT(m["landmarks_mapped"].get<int>(), 100);
  }
  const auto bad = RunCli("run --isam " + kVictoria + " --association mle --out " +
                          FreshDir("victoria_bad").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("--association"), std::string::npos) << bad.output;
}

// Issue 11: FastSLAM 2.0 with 100 particles and the shipped configuration (delayed sampling, each
// particle associating by itself) maps the park as the EKF does: 0.99 against the merged ids,
// the landmark count within 5 % of the file's 151. Without delayed sampling it closed the park's
// loops on three seeds of eight (docs/victoria_park.md); seeds 1-8 all pass with it.
TEST(VictoriaPark, FastSlam2MapsTheParkWithoutTheFileIds) {
  if (!fs::exists(kVictoria)) GTEST_SKIP() << "no " << kVictoria;
  const fs::path dir = FreshDir("victoria_fastslam2");
  const auto r = RunCli("run --isam " + kVictoria + " --config " + std::string(SLAMKIT_SOURCE_DIR) +
                        "/configs/victoria_park.yaml --filter fastslam2 --particles 100 "
                        "--association nn --seed 2 --no-figures --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto m = nlohmann::json::parse(ReadText(dir / "metrics.json"));
  EXPECT_EQ(m["params"]["fastslam"]["delayed_sampling"], true);
  EXPECT_GE(m["association_agreement_merged"].get<double>(), 0.99);
  EXPECT_NEAR(m["landmarks_mapped"].get<double>(), 151.0, 0.05 * 151.0);
  EXPECT_LT(m["smoothed_reference"]["map_rmse_m"].get<double>(), 3.0);
}

// Issue 11: the EKF with joint-compatibility association and the shipped configuration maps the
// park without the file's ids. The file gives three trees two ids each (never sighted together,
// within the gate of each other), so against its ids one-to-one a correct map scores about 0.97;
// against the ids its data can tell apart it must reach 0.99, with the landmark count within
// 5 % of the file's 151.
TEST(VictoriaPark, JointCompatibilityMapsTheParkWithoutTheFileIds) {
  if (!fs::exists(kVictoria)) GTEST_SKIP() << "no " << kVictoria;
  const fs::path dir = FreshDir("victoria_jcbb_config");
  const auto r = RunCli("run --isam " + kVictoria + " --config " + std::string(SLAMKIT_SOURCE_DIR) +
                        "/configs/victoria_park.yaml --no-figures --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto m = nlohmann::json::parse(ReadText(dir / "metrics.json"));
  EXPECT_EQ(m["association"], "jcbb");
  EXPECT_GE(m["association_agreement_merged"].get<double>(), 0.99);
  EXPECT_GE(m["association_agreement"].get<double>(), 0.96);
  EXPECT_NEAR(m["landmarks_mapped"].get<double>(), 151.0, 0.05 * 151.0);
  EXPECT_EQ(m["reference_merges"].size(), 3u);
  EXPECT_EQ(m["params"]["odometry"]["stt"], 0.11);
  // The park's odometry turns about 0.0019 rad per metre less than the car (docs/victoria_park.md);
  // an estimate that closes the loops shows it, and it explains a third of the turn error.
  const auto& drift = m["odometry_heading_drift"];
  EXPECT_NEAR(drift["fitted_rad_per_m"].get<double>(), 0.0019, 0.0003);
  EXPECT_LT(drift["rms_after_rad"].get<double>(), 0.8 * drift["rms_before_rad"].get<double>());
  // Against the least-squares solution with the file's ids (dead reckoning strays about 150 m
  // rms from it): the filtered path within 2 m rms, the final map within 3 m.
  const auto& ref = m["smoothed_reference"];
  EXPECT_LT(ref["ate_rmse_m"].get<double>(), 2.0);
  EXPECT_LT(ref["map_rmse_m"].get<double>(), 3.0);
  EXPECT_GE(ref["landmarks_compared"].get<int>(), 140);
  EXPECT_EQ(drift["windows"], 69);
  // A run that is right does not warn (issue 31 part 6).
  EXPECT_EQ(m["innovation_check"]["verdict"], "consistent");
  EXPECT_EQ(m["innovation_check"]["warning"], "");
  EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
}

// Issue 31 part 6: without --config the file's own noise (a fixed 1 cm, 0.11 deg per step) lets
// the path drift past the gates; the run ends 101 m from the reference. It must say so, name the
// keys that fix it, and record the check.
TEST(VictoriaPark, TheFileOwnNoiseWarnsAndNamesTheKeys) {
  if (!fs::exists(kVictoria)) GTEST_SKIP() << "no " << kVictoria;
  const fs::path dir = FreshDir("victoria_own_noise");
  const auto r = RunCli("run --isam " + kVictoria + " --no-figures --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("slamkit: warning:"), std::string::npos) << r.output;
  for (const char* key : {"odometry.srr", "--odometry-noise", "configs/victoria_park.yaml"}) {
    EXPECT_NE(r.output.find(key), std::string::npos) << key;
  }
  const auto m = nlohmann::json::parse(ReadText(dir / "metrics.json"));
  const auto& check = m["innovation_check"];
  EXPECT_EQ(check["verdict"], "noise_too_small");
  EXPECT_EQ(check["reference_landmarks"], 151);
  EXPECT_GT(check["reobservations_outside_gate_share"].get<double>(),
            2.0 * check["expected_share"].get<double>());
  EXPECT_NE(check["warning"].get<std::string>().find("too small"), std::string::npos);
  // It is what the warning says: the run is far off.
  EXPECT_GT(m["smoothed_reference"]["ate_rmse_m"].get<double>(), 20.0);
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

// Issue 9: --reference compares with a per-scan reference file, paired by time or by index; a
// pairing the file's stamps cannot support, or a pose count that is not the scan count, fails
// before the run (exit 2, no output), naming the file and the way out.

}  // namespace
}  // namespace slamkit
