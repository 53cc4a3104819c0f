#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>

#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit {
namespace {

using testing::FreshDir;
using testing::ReadText;
using testing::RunCli;
namespace fs = std::filesystem;

const std::string& kShort = testing::kShortScenario;

TEST(Cli, HelpListsSubcommandsAndEachHasHelp) {
  const auto top = RunCli("--help");
  EXPECT_EQ(top.exit_code, 0);
  for (const char* sub : {"demo", "mc", "run", "grid", "gridsim"}) {
    EXPECT_NE(top.output.find(sub), std::string::npos) << sub;
    const auto help = RunCli(std::string(sub) + " --help");
    EXPECT_EQ(help.exit_code, 0) << sub;
    EXPECT_NE(help.output.find("--out"), std::string::npos) << sub;
  }
}

TEST(Cli, MalformedScenarioExitsTwoNamingFileAndKey) {
  const fs::path dir = FreshDir("bad_scenario");
  std::ofstream(dir / "bad.yaml") << "name: bad\ndt_s: 0.1\nsensor:\n  max_range_m: fast\n";
  const auto r = RunCli("mc --config " + (dir / "bad.yaml").string() + " --runs 2 --out " +
                        (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.yaml"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("max_range_m"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(":4"), std::string::npos) << r.output;  // the line of the key
  EXPECT_FALSE(fs::exists(dir / "out" / "metrics.json"));
}

TEST(Cli, LandmarkCsvWithNanExitsTwoNamingFileAndLine) {
  const fs::path dir = FreshDir("nan_csv");
  std::ofstream(dir / "world.csv") << "id,x_m,y_m\n0,1.0,2.0\n1,nan,3.0\n";
  std::ofstream(dir / "csv.yaml")
      << "name: csv\nworld:\n  kind: csv\n  landmarks_csv: world.csv\nroute:\n"
         "  waypoints_m: [[0, 0], [10, 0]]\n";
  const auto r = RunCli("mc --config " + (dir / "csv.yaml").string() + " --runs 1 --out " +
                        (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("world.csv"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(":3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("x_m"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(Cli, MalformedCarmenLogExitsTwoNamingFileLineAndField) {
  const fs::path dir = FreshDir("bad_log");
  std::ofstream(dir / "bad.clf") << "ODOM 0 0 0 0 0 0 1.0 host 0\n"
                                 << "FLASER 3 1.0 2.0 nan 0 0 0 0 0 0 1.1 host 0\n";
  const auto r = RunCli("grid --log " + (dir / "bad.clf").string() + " --out " +
                        (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.clf:2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("r3"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// gridsim's bad inputs fail before the simulation, so no output directory is made.
TEST(Cli, GridSimBadInputsExitTwoNamingTheProblem) {
  const fs::path dir = FreshDir("gridsim_bad");
  std::ofstream(dir / "map.pgm", std::ios::binary) << "P5\n4 4\n255\n" << std::string(10, '\0');
  std::ofstream(dir / "map.yaml") << "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n";
  std::ofstream(dir / "nores.yaml") << "image: map.pgm\norigin: [0, 0, 0]\n";
  std::ofstream(dir / "route.txt") << "1 1\n2 oops\n";
  std::ofstream(dir / "walls.txt") << "poly 0 0 4 0 4 4 0 4\n1 nan 2 2\n";
  std::ofstream(dir / "good_route.txt") << "1 1\n3 1\n";
  const std::string out = " --out " + (dir / "out").string();
  const std::pair<std::string, std::vector<std::string>> cases[] = {
      {"--plan " + (dir / "map.yaml").string(), {"--waypoints"}},
      {"--plan " + (dir / "map.yaml").string() + " --waypoints " + (dir / "route.txt").string(),
       {"map.pgm", "truncated pixel data"}},
      {"--plan " + (dir / "nores.yaml").string() + " --waypoints " + (dir / "route.txt").string(),
       {"nores.yaml", "resolution"}},
      {"--waypoints " + (dir / "route.txt").string(), {"route.txt:2", "'y'"}},
      {"--plan " + (dir / "none.yaml").string() + " --waypoints " + (dir / "route.txt").string(),
       {"none.yaml"}},
      {"--plan " + (dir / "walls.txt").string(), {"--waypoints"}},
      {"--plan " + (dir / "walls.txt").string() + " --waypoints " +
           (dir / "good_route.txt").string(),
       {"walls.txt:2", "'y1'"}},
      {"--speed 5", {"--speed"}},
      {"--particles 0", {"--particles"}}};
  for (const auto& [args, parts] : cases) {
    const auto r = RunCli("gridsim " + args + out);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.output;
    for (const std::string& part : parts) {
      EXPECT_NE(r.output.find(part), std::string::npos) << args << "\n" << r.output;
    }
    EXPECT_FALSE(fs::exists(dir / "out")) << args;
  }
}

// Same seed, one or two threads: every output file is identical, and metrics.json differs only
// in its wall-time keys.
TEST(Cli, OutputsAreIdenticalForOneAndTwoThreads) {
  const fs::path dir = FreshDir("determinism");
  for (const char* t : {"1", "2"}) {
    const auto r = RunCli("mc --config " + kShort + " --runs 4 --seed 5 --no-figures --threads " +
                          t + " --out " + (dir / t).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir / "1")) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), dir / "1");
    if (rel == "metrics.json") continue;
    EXPECT_EQ(ReadText(entry.path()), ReadText(dir / "2" / rel)) << rel;
    ++files;
  }
  // world.csv, consistency.csv, five files per run and run_0's map history
  EXPECT_EQ(files, 2 + 4 * 5 + 1);
  auto strip = [](nlohmann::json j) {
    j.erase("step_time_mean_s");
    j.erase("step_time_max_s");
    for (auto& run : j["per_run"]) {
      run.erase("step_time_mean_s");
      run.erase("step_time_max_s");
    }
    return j;
  };
  const auto m1 = nlohmann::json::parse(ReadText(dir / "1" / "metrics.json"));
  const auto m2 = nlohmann::json::parse(ReadText(dir / "2" / "metrics.json"));
  EXPECT_EQ(strip(m1), strip(m2));
  for (const char* key : {"runs", "position_rmse_m", "heading_rmse_rad", "anees", "anees_band",
                          "landmarks_mapped", "step_time_mean_s", "step_time_max_s", "per_run"}) {
    EXPECT_TRUE(m1.contains(key)) << key;
  }
  EXPECT_EQ(m1["per_run"].size(), 4u);
}

// Issue 11: `mc --filter` runs FastSLAM on the scenario through the same harness and records it;
// `run --filter` refuses JCBB, which is the EKF's association, before reading anything.
TEST(Cli, TheLandmarkFilterIsChosenByName) {
  const fs::path dir = FreshDir("mc_filters");
  nlohmann::json m[2];
  const char* filters[] = {"ekf", "fastslam2"};
  for (int i = 0; i < 2; ++i) {
    const auto r = RunCli("mc --config " + kShort + " --runs 2 --no-figures --particles 10 " +
                          "--filter " + filters[i] + " --out " + (dir / filters[i]).string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    m[i] = nlohmann::json::parse(ReadText(dir / filters[i] / "metrics.json"));
    EXPECT_EQ(m[i]["filter"], filters[i]);
  }
  EXPECT_FALSE(m[0].contains("particles"));
  EXPECT_EQ(m[1]["particles"], 10);
  EXPECT_NE(m[0]["position_rmse_m"], m[1]["position_rmse_m"]);
  const auto bad = RunCli("mc --config " + kShort + " --filter ukf --out " + (dir / "bad").string());
  EXPECT_EQ(bad.exit_code, 2);
  const auto jcbb = RunCli("run --isam " + kShort + " --filter fastslam2 --association jcbb " +
                           "--out " + (dir / "isam").string());
  EXPECT_EQ(jcbb.exit_code, 2);
  EXPECT_NE(jcbb.output.find("--filter"), std::string::npos) << jcbb.output;
  EXPECT_FALSE(fs::exists(dir / "isam"));
}

// An iSAM log of a circle (radius 5 m, 60 steps of 0.5 m) around four trees, each sighted from
// every pose without noise.
fs::path WriteCircleIsamLog(const fs::path& dir) {
  const double tree[4][2] = {{0.0, 5.0}, {2.0, 5.0}, {0.0, 7.0}, {-2.0, 4.0}};
  std::ofstream out(dir / "circle.isam");
  double x = 0.0, y = 0.0, theta = 0.0;
  for (int i = 0; i < 60; ++i) {
    out << "ODOMETRY " << i << " " << i + 1 << " 0.5 0 0.1 0.0001 0 0 0.0001 0 0.0001\n";
    x += 0.5 * std::cos(theta);
    y += 0.5 * std::sin(theta);
    theta += 0.1;
    for (int k = 0; k < 4; ++k) {
      const double dx = tree[k][0] - x, dy = tree[k][1] - y;
      out << "LANDMARK " << i + 1 << " " << 1000 + k << " "
          << std::cos(theta) * dx + std::sin(theta) * dy << " "
          << -std::sin(theta) * dx + std::cos(theta) * dy << " 0.04 0 0.04\n";
    }
  }
  return dir / "circle.isam";
}

// Issue 11: `run --filter fastslam2 --seed S` gives the same run for the same seed, another for
// another seed, and records the seed.
TEST(Cli, FastSlamRunsAreReproducedByTheirSeed) {
  const fs::path dir = FreshDir("run_seed");
  const fs::path log = WriteCircleIsamLog(dir);
  std::string estimate[3];
  const int seeds[3] = {3, 3, 4};
  for (int i = 0; i < 3; ++i) {
    const fs::path out = dir / std::to_string(i);
    const auto r = RunCli("run --isam " + log.string() + " --filter fastslam2 --particles 5 " +
                          "--seed " + std::to_string(seeds[i]) + " --threads " +
                          std::to_string(i + 1) + " --no-figures --out " + out.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    estimate[i] = ReadText(out / "estimate.tum");
    EXPECT_EQ(nlohmann::json::parse(ReadText(out / "metrics.json"))["seed"], seeds[i]);
  }
  EXPECT_EQ(estimate[0], estimate[1]);
  EXPECT_NE(estimate[0], estimate[2]);
}

// Issue 8 item 2: a closed or full stderr must not abort the run (the progress printer and the
// error handler write without throwing).

}  // namespace
}  // namespace slamkit
