// `slamkit study` and `slamkit mc --planner` (issue 11): the command line around RunStudy and
// the closed-loop Monte Carlo.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit {
namespace {

using testing::FreshDir;
using testing::ReadText;
using testing::RunCli;
namespace fs = std::filesystem;

const std::string kSwslam = std::string(SLAMKIT_SOURCE_DIR) + "/configs/swslam.yaml";

// configs/swslam.yaml with one dense cluster and a short route past it and back (about 40 s).
fs::path WriteTinyConfig(const fs::path& dir) {
  const fs::path path = dir / "tiny.yaml";
  std::ofstream(path) << R"(name: tiny
dt_s: 0.025
max_steps: 4000
world:
  kind: clusters
  seed: 2024
  clusters:
    - {center_m: [30, 28], sigma_m: 5, count: 20}
    - {center_m: [50, 30], sigma_m: 25, count: 10}
vehicle: {motion: car_like, wheelbase_m: 4.0, sigma_v_mps: 0.3, sigma_steer_deg: 3.0}
controller: {speed_mps: 3.0, max_steer_deg: 30.0, max_steer_rate_degps: 20.0}
route: {waypoints_m: [[8, 8], [30, 3], [52, 3], [60, 20]], loops: 1, switch_distance_m: 3.0}
initial_pose: {x_m: 8, y_m: 8, theta_deg: -12.8}
sensor: {max_range_m: 30.0, fov_deg: 180.0, sigma_range_m: 0.1, sigma_bearing_deg: 1.0,
         period_steps: 8}
ekf: {known_association: false, gate_chi2: 9.21, new_landmark_chi2: 13.82}
planner: {kind: swslam, min_cluster_landmarks: 6, revisit_radius_m: 15.0}
)";
  return path;
}

TEST(StudyCli, HelpNamesTheOptions) {
  const auto help = RunCli("study --help");
  EXPECT_EQ(help.exit_code, 0);
  for (const char* option :
       {"--config", "--runs", "--out", "--seed", "--threads", "--particles", "--filter"}) {
    EXPECT_NE(help.output.find(option), std::string::npos) << option;
  }
  EXPECT_NE(RunCli("--help").output.find("study"), std::string::npos);
  EXPECT_NE(RunCli("mc --help").output.find("--planner"), std::string::npos);
}

// Bad arguments fail before anything runs, naming the option, and leave no output.
TEST(StudyCli, BadArgumentsExitTwoNamingTheOption) {
  const fs::path dir = FreshDir("study_bad");
  const std::string out = " --out " + (dir / "out").string();
  const std::pair<std::string, std::string> cases[] = {
      {"study --config " + kSwslam + " --runs 0", "--runs"},
      {"study --config " + kSwslam + " --runs -3", "--runs"},
      {"study --config " + kSwslam + " --runs 1000000000", "--runs"},
      {"study --config " + kSwslam + " --filter ukf", "--filter"},
      {"study --config " + kSwslam + " --filter ekf", "--filter"},
      {"study --config " + kSwslam + " --particles 0", "--particles"},
      {"study --config " + (dir / "none.yaml").string(), "--config"},
      {"mc --config " + kSwslam + " --planner detour", "--planner"}};
  for (const auto& [args, option] : cases) {
    const auto r = RunCli(args + out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(option), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "out")) << args;
  }
}

TEST(StudyCli, WritesTablesJsonAndFigures) {
  const fs::path dir = FreshDir("study_tiny");
  const fs::path config = WriteTinyConfig(dir);
  const auto r =
      RunCli("study --config " + config.string() +
             " --runs 2 --particles 5 --threads 2 --seed 3 --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file :
       {"table1.csv", "table2.csv", "table3.csv", "table4.csv", "table5.csv", "tables.md",
        "sections.csv", "nees.csv", "study.json", "metrics.json", "nees.png", "path.png"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  }
  const auto study = nlohmann::json::parse(ReadText(dir / "out" / "study.json"));
  EXPECT_EQ(study["runs"], 2);
  EXPECT_EQ(study["particles"], 5);
  ASSERT_EQ(study["methods"].size(), 3u);
  EXPECT_EQ(study["methods"][1]["filter"], "fastslam2");
  EXPECT_EQ(study["methods"][2]["planner"], "swslam");
  // Progress lines name each method on stderr; the summary goes to stdout.
  for (const char* part : {"SWSLAM runs", "EKF-SLAM runs", "FastSLAM 2.0 runs", "wrote"}) {
    EXPECT_NE(r.output.find(part), std::string::npos) << part << "\n" << r.output;
  }
}

// `mc` follows the config's planner section unless --planner says otherwise, and records it.
TEST(StudyCli, McRecordsThePlannerAndItsSections) {
  const fs::path dir = FreshDir("mc_planner");
  const fs::path config = WriteTinyConfig(dir);
  nlohmann::json m[2];
  const char* flags[] = {"", " --planner route"};
  for (int i = 0; i < 2; ++i) {
    const fs::path out = dir / std::to_string(i);
    const auto r = RunCli("mc --config " + config.string() + " --runs 2 --no-figures --out " +
                          out.string() + flags[i]);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    m[i] = nlohmann::json::parse(ReadText(out / "metrics.json"));
  }
  EXPECT_EQ(m[0]["planner"], "swslam");
  EXPECT_EQ(m[1]["planner"], "route");
  EXPECT_EQ(m[0]["filter"], "ekf");
  ASSERT_FALSE(m[0]["sections"].empty());
  for (const char* key : {"section", "runs", "observations", "periods", "landmarks",
                          "observations_per_period", "observations_per_landmark"}) {
    EXPECT_TRUE(m[0]["sections"][0].contains(key)) << key;
  }
  EXPECT_FALSE(m[0]["per_run"][0]["detours"].empty());
  EXPECT_TRUE(m[1]["per_run"][0]["detours"].empty());
  // The detour makes SWSLAM's runs longer than the route's.
  EXPECT_GT(m[0]["steps"].get<int>(), m[1]["steps"].get<int>());
}

}  // namespace
}  // namespace slamkit
