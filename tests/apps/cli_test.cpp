#include <gtest/gtest.h>

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

const std::string kShort = std::string(SLAMKIT_SOURCE_DIR) + "/configs/short.yaml";

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
  EXPECT_EQ(files, 2 + 4 * 4);
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

}  // namespace
}  // namespace slamkit
