// End-to-end runs of `slamkit suite` and `slamkit grid` on the CARMEN suite in
// ../shared/datasets (read in place, never copied).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit {
namespace {

using testing::FreshDir;
using testing::ReadText;
using testing::RunCli;
namespace fs = std::filesystem;

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
