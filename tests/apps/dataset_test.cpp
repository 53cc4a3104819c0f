// End-to-end runs on the real data sets in ../shared/datasets (read in place, never copied).
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
TEST(Suite, GridComparesWithAReferenceFileByTimeOrIndex) {
  const std::string suite = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/suite/";
  if (!fs::exists(suite + "freiburg-101.log.gz")) GTEST_SKIP() << "no suite";
  const fs::path dir = FreshDir("suite_reference");
  const std::string f101 = "grid --log " + suite + "freiburg-101.log.gz --reference " + suite +
                           "freiburg-101.reference.txt --max-scans 40 --particles 5";
  const auto by_time = RunCli(f101 + " --out " + (dir / "time").string());
  ASSERT_EQ(by_time.exit_code, 0) << by_time.output;
  const auto by_index = RunCli(f101 + " --pair-by index --out " + (dir / "index").string());
  ASSERT_EQ(by_index.exit_code, 0) << by_index.output;
  const auto t = nlohmann::json::parse(ReadText(dir / "time" / "metrics.json"));
  const auto i = nlohmann::json::parse(ReadText(dir / "index" / "metrics.json"));
  EXPECT_EQ(t["pair_by"], "time");
  EXPECT_EQ(i["pair_by"], "index");
  // The reference has one pose per scan at the scan's time, so both pairings agree.
  EXPECT_DOUBLE_EQ(t["ate_rmse_m"].get<double>(), i["ate_rmse_m"].get<double>());
  EXPECT_LT(t["ate_rmse_m"].get<double>(), 0.5);

  // csail's stamps repeat (6 significant digits): by time is refused.
  const auto csail = RunCli("grid --log " + suite + "csail.log.gz --reference " + suite +
                            "csail.reference.txt --out " + (dir / "csail").string());
  EXPECT_EQ(csail.exit_code, 2) << csail.output;
  EXPECT_NE(csail.output.find("csail.reference.txt"), std::string::npos) << csail.output;
  EXPECT_NE(csail.output.find("--pair-by index"), std::string::npos) << csail.output;
  // Another log's reference by index: the pose count is not the scan count.
  const auto wrong = RunCli("grid --log " + suite + "csail.log.gz --reference " + suite +
                            "freiburg-101.reference.txt --pair-by index --out " +
                            (dir / "wrong").string());
  EXPECT_EQ(wrong.exit_code, 2) << wrong.output;
  EXPECT_NE(wrong.output.find("292 poses for the 406 scans"), std::string::npos) << wrong.output;
  EXPECT_FALSE(fs::exists(dir / "csail"));
  EXPECT_FALSE(fs::exists(dir / "wrong"));
}

// Issue 9: csail-corrected's odometry fields hold the corrected poses; comparing with them must
// say that it measures nothing.
TEST(Suite, ReferenceFromLogWarnsWhenTheOdometryIsTheReference) {
  const std::string carmen = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/";
  if (!fs::exists(carmen + "csail-corrected.log.gz")) GTEST_SKIP() << "no csail-corrected";
  const fs::path dir = FreshDir("suite_from_log");
  const auto corrected = RunCli("grid --log " + carmen + "csail-corrected.log.gz --max-scans 20 "
                                "--particles 3 --reference-from-log --out " +
                                (dir / "c").string());
  ASSERT_EQ(corrected.exit_code, 0) << corrected.output;
  EXPECT_NE(corrected.output.find("measures nothing"), std::string::npos) << corrected.output;
  // A log whose poses are not its odometry (here a constant offset of 5 cm): no warning.
  {
    std::ofstream log(dir / "distinct.clf");
    for (int k = 0; k < 6; ++k) {
      log << "FLASER 3 1.0 2.0 3.0 " << 0.1 * k + 0.05 << " 0 0 " << 0.1 * k << " 0 0 " << k
          << " host " << k << "\n";
    }
  }
  const auto distinct = RunCli("grid --log " + (dir / "distinct.clf").string() +
                               " --particles 3 --reference-from-log --out " + (dir / "d").string());
  ASSERT_EQ(distinct.exit_code, 0) << distinct.output;
  EXPECT_EQ(distinct.output.find("measures nothing"), std::string::npos) << distinct.output;
}

// Issue 9: `slamkit suite` runs every log of a manifest for every seed and summarises them; a run
// that fails is recorded as failed (exit 1 overall) without stopping the others.
TEST(Suite, RunsEveryLogAndSeedAndRecordsAFailedRun) {
  const std::string suite = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/suite/";
  if (!fs::exists(suite + "freiburg-101.log.gz")) GTEST_SKIP() << "no suite";
  const fs::path dir = FreshDir("suite_run");
  std::ofstream(dir / "broken.clf") << "ODOM 0 0 0 0 0 0 1.0 host 0\n";  // no scan at all
  std::ofstream(dir / "suite.yaml")
      << "root: " << suite << "\nlogs:\n"
      << "  - {name: f101, log: freiburg-101.log.gz, reference: freiburg-101.reference.txt}\n"
      << "  - {name: csail, log: csail.log.gz, reference: csail.reference.txt, pair_by: index}\n"
      << "  - {name: broken, log: " << (dir / "broken.clf").string() << "}\n";
  const auto r = RunCli("suite --manifest " + (dir / "suite.yaml").string() +
                        " --seeds 1-2 --max-scans 25 --particles 3 --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("6 runs (3 logs x 2 seeds), 2 failed"), std::string::npos) << r.output;
  const auto summary = nlohmann::json::parse(ReadText(dir / "out" / "summary.json"));
  ASSERT_EQ(summary["runs"].size(), 6u);
  for (const auto& run : summary["runs"]) {
    const bool broken = run["log"] == "broken";
    EXPECT_EQ(run["status"], broken ? "failed" : "ok") << run.dump();
    if (broken) {
      EXPECT_EQ(run["exit_code"], 2);
      EXPECT_NE(run["failure"].get<std::string>().find("no laser scan"), std::string::npos);
    } else {
      EXPECT_EQ(run["metrics"]["scans"], 25);
      EXPECT_GT(run["metrics"]["ate_rmse_m"].get<double>(), 0.0);
      EXPECT_GT(run["metrics"]["odometry_ate_rmse_m"].get<double>(), 0.0);
      EXPECT_GT(run["peak_rss_mib"].get<double>(), 1.0);
    }
  }
  EXPECT_EQ(summary["logs"][0]["completed"], 2);
  EXPECT_EQ(summary["logs"][2]["failed"], 2);
  const std::string csv = ReadText(dir / "out" / "summary.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7);  // header and 6 runs
  EXPECT_NE(ReadText(dir / "out" / "summary.md").find("| csail | 2 |"), std::string::npos);
  EXPECT_GT(fs::file_size(dir / "out" / "maps.png"), 10000u);  // 6 panels, 2 of them "no map"
  for (const char* seed : {"seed_1", "seed_2"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / "runs" / "f101" / seed / "map.pgm")) << seed;
  }
}

// --logs picks logs of the manifest by name, and --config reaches every run (its parameters are
// in each run's metrics.json).
TEST(Suite, RunsTheNamedLogsWithTheGivenConfig) {
  const std::string suite = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/suite/";
  if (!fs::exists(suite + "freiburg-101.log.gz")) GTEST_SKIP() << "no suite";
  const fs::path dir = FreshDir("suite_logs");
  std::ofstream(dir / "suite.yaml")
      << "root: " << suite << "\nlogs:\n"
      << "  - {name: f101, log: freiburg-101.log.gz, reference: freiburg-101.reference.txt}\n"
      << "  - {name: csail, log: csail.log.gz, reference: csail.reference.txt, pair_by: index}\n";
  std::ofstream(dir / "grid.yaml") << "particles: 2\nusable_range_m: 12.5\n";
  const std::string common = "suite --manifest " + (dir / "suite.yaml").string() +
                             " --max-scans 20 --config " + (dir / "grid.yaml").string();
  const auto r = RunCli(common + " --logs csail --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto summary = nlohmann::json::parse(ReadText(dir / "out" / "summary.json"));
  ASSERT_EQ(summary["runs"].size(), 1u);
  const auto& metrics = summary["runs"][0]["metrics"];
  EXPECT_EQ(summary["runs"][0]["log"], "csail");
  EXPECT_EQ(metrics["particles"], 2);
  EXPECT_EQ(metrics["usable_range_m"], 12.5);
  const auto unknown = RunCli(common + " --logs csail,intel --out " + (dir / "bad").string());
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  EXPECT_NE(unknown.output.find("--logs: no log 'intel' in " + (dir / "suite.yaml").string() +
                                " (its logs: f101, csail)"),
            std::string::npos)
      << unknown.output;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}

TEST(Suite, BadSeedsAndManifestsExitTwoBeforeAnyRun) {
  const fs::path dir = FreshDir("suite_bad");
  std::ofstream(dir / "suite.yaml") << "logs:\n  - {name: a, log: nowhere.clf}\n";
  const auto missing = RunCli("suite --manifest " + (dir / "suite.yaml").string() + " --out " +
                              (dir / "out").string());
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("suite.yaml:2: key 'logs[0].log': no such file"),
            std::string::npos) << missing.output;
  const std::string manifest = std::string(SLAMKIT_SOURCE_DIR) + "/configs/carmen_suite.yaml";
  for (const char* seeds : {"5-1", "x", "1-", "-3", "1,,2", "1-5000"}) {
    const auto r = RunCli("suite --manifest " + manifest + " --seeds=" + seeds + " --out " +
                          (dir / "out").string());
    EXPECT_EQ(r.exit_code, 2) << seeds << ": " << r.output;
    EXPECT_NE(r.output.find("expected seeds such as 1-5"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Reads the times and positions of a TUM file.
std::vector<std::array<double, 3>> ReadTum(const fs::path& path) {
  std::vector<std::array<double, 3>> out;
  std::ifstream in(path);
  double t, x, y, z, qx, qy, qz, qw;
  while (in >> t >> x >> y >> z >> qx >> qy >> qz >> qw) out.push_back({t, x, y});
  return out;
}

// Issue 9: trajectory.tum must load in evo (strictly increasing times) even from csail's repeated
// stamps, with a warning; odometry.tum is the raw odometry in the same frame; --frame odometry
// keeps the log's frame instead of starting at the origin.
TEST(Suite, TumOutputsHaveIncreasingTimesAndTheAskedFrame) {
  const std::string suite = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/suite/";
  if (!fs::exists(suite + "csail.log.gz")) GTEST_SKIP() << "no suite";
  const fs::path dir = FreshDir("suite_tum");
  const std::string csail = "grid --log " + suite + "csail.log.gz --max-scans 30 --particles 3";
  const auto origin = RunCli(csail + " --out " + (dir / "origin").string());
  ASSERT_EQ(origin.exit_code, 0) << origin.output;
  EXPECT_NE(origin.output.find("timestamps cannot pair poses"), std::string::npos) << origin.output;
  const auto odometry = RunCli(csail + " --frame odometry --out " + (dir / "odom").string());
  ASSERT_EQ(odometry.exit_code, 0) << odometry.output;
  for (const char* run : {"origin", "odom"}) {
    for (const char* file : {"trajectory.tum", "odometry.tum"}) {
      const auto poses = ReadTum(dir / run / file);
      ASSERT_EQ(poses.size(), 30u) << run << file;
      for (std::size_t i = 1; i < poses.size(); ++i) {
        ASSERT_GT(poses[i][0], poses[i - 1][0]) << run << file << i;
      }
    }
  }
  const auto est = ReadTum(dir / "origin" / "trajectory.tum");
  const auto odo = ReadTum(dir / "origin" / "odometry.tum");
  EXPECT_EQ(est[0][1], 0.0);
  EXPECT_EQ(odo[0][1], 0.0);
  EXPECT_EQ(odo[0][2], 0.0);
  // In the log's frame both start at the log's first odometry pose, not at the origin.
  const auto est_log = ReadTum(dir / "odom" / "trajectory.tum");
  const auto odo_log = ReadTum(dir / "odom" / "odometry.tum");
  EXPECT_NEAR(est_log[0][1], odo_log[0][1], 1e-9);
  EXPECT_NEAR(est_log[0][2], odo_log[0][2], 1e-9);
  EXPECT_GT(std::hypot(odo_log[0][1], odo_log[0][2]), 1e-3);
  // The odometry in the two frames differs by a rigid motion (the filter's run need not: the grid
  // is axis-aligned, so a rotated start discretises the walls differently).
  const double d_origin = std::hypot(odo[29][1] - odo[0][1], odo[29][2] - odo[0][2]);
  const double d_log = std::hypot(odo_log[29][1] - odo_log[0][1], odo_log[29][2] - odo_log[0][2]);
  EXPECT_GT(d_origin, 1.0);
  EXPECT_NEAR(d_origin, d_log, 1e-6);
}

// Issue 9: --config gives the filter's parameters from a YAML file; metrics.json records the
// effective parameters, the log and the version, so that a run can be reproduced from its output.
TEST(Suite, GridConfigFileAndReproducibleMetrics) {
  const std::string suite = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/suite/";
  if (!fs::exists(suite + "edmonton.log.gz")) GTEST_SKIP() << "no suite";
  const fs::path dir = FreshDir("suite_config");
  std::ofstream(dir / "grid.yaml") << "particles: 4\nmotion: {srr: 0.08}\nproposal: scan_match\n";
  const std::string grid = "grid --log " + suite + "edmonton.log.gz --max-scans 20 --config " +
                           (dir / "grid.yaml").string();
  const auto r = RunCli(grid + " --seed 9 --out " + (dir / "a").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto m = nlohmann::json::parse(ReadText(dir / "a" / "metrics.json"));
  EXPECT_EQ(m["params"]["particles"], 4);
  EXPECT_EQ(m["params"]["seed"], 9);  // --seed overrides the file
  EXPECT_EQ(m["params"]["motion"]["srr"], 0.08);
  EXPECT_EQ(m["params"]["proposal"], "scan_match");
  EXPECT_NE(m["log"].get<std::string>().find("edmonton.log.gz"), std::string::npos);
  EXPECT_FALSE(m["version"].get<std::string>().empty());
  // The recorded parameters, as a config, reproduce the run's trajectory.
  std::ofstream(dir / "again.yaml") << m["params"].dump(2);
  const auto again = RunCli("grid --log " + suite + "edmonton.log.gz --max-scans 20 --config " +
                            (dir / "again.yaml").string() + " --out " + (dir / "b").string());
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(ReadText(dir / "a" / "trajectory.txt"), ReadText(dir / "b" / "trajectory.txt"));
  // A filter flag beside --config is refused; a bad key names the file and key.
  const auto both = RunCli(grid + " --srr 0.1 --out " + (dir / "c").string());
  EXPECT_EQ(both.exit_code, 2) << both.output;
  EXPECT_NE(both.output.find("excludes"), std::string::npos) << both.output;
  std::ofstream(dir / "bad.yaml") << "motion:\n  srq: 1\n";
  const auto bad = RunCli("grid --log " + suite + "edmonton.log.gz --config " +
                          (dir / "bad.yaml").string() + " --out " + (dir / "d").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("bad.yaml:2"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("srq"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(dir / "d"));
  const auto version = RunCli("--version");
  EXPECT_EQ(version.exit_code, 0);
  EXPECT_NE(version.output.find("slamkit "), std::string::npos) << version.output;
}

}  // namespace
}  // namespace slamkit
