// `slamkit explore` end to end: the shipped experiment, shortened, and its input errors.
#include <gtest/gtest.h>

#include <algorithm>
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

const fs::path kConfig = fs::path(SLAMKIT_SOURCE_DIR) / "configs/office_selection.yaml";

// The shipped config with its world path made absolute and the line starting with
// `replace_line` (if given) replaced by `with`.
fs::path ConfigWith(const fs::path& dir, const std::string& replace_line,
                    const std::string& with) {
  std::string text = ReadText(kConfig);
  const std::string world = (fs::path(SLAMKIT_SOURCE_DIR) / "examples/plans/office.txt").string();
  text.replace(text.find("../examples/plans/office.txt"), 28, world);
  if (!replace_line.empty()) {
    const std::size_t at = text.find(replace_line);
    text.replace(at, text.find('\n', at) - at, with);
  }
  const fs::path path = dir / "explore.yaml";
  std::ofstream(path) << text;
  return path;
}

TEST(Explore, ShortRunWritesItsFilesAndBeatsOdometry) {
  const fs::path dir = FreshDir("explore_run");
  const fs::path config = ConfigWith(dir, "max_time_s:", "max_time_s: 60.0");
  const auto r = RunCli("explore --config " + config.string() + " --policy all --seed 3 --out " +
                        (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"trajectory.tum", "truth.tum", "odometry.tum", "lines.csv", "map.png",
                           "metrics.json"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  }
  const auto m = nlohmann::json::parse(ReadText(dir / "out" / "metrics.json"));
  EXPECT_EQ(m["params"]["selection"]["policy"], "all");  // the option overrides the file
  EXPECT_EQ(m["params"]["seed"], 3);
  EXPECT_GT(m["steps"].get<int>(), 100);
  EXPECT_LT(m["mean_error_m"].get<double>(), m["odometry_mean_error_m"].get<double>());
  EXPECT_GT(m["lines"].get<int>(), 3);
  EXPECT_GE(m["open_loop_time_s"].get<double>(), 0.0);
}

TEST(Explore, ConfigMistakesNameTheFileLineAndKey) {
  const fs::path dir = FreshDir("explore_errors");
  const fs::path bad_key = ConfigWith(dir, "flops_per_second:", "flops_per_secnd: 1.0e9");
  const auto r = RunCli("explore --config " + bad_key.string() + " --out " +
                        (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("explore.yaml:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("flops_per_secnd"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
  const fs::path bad_policy = ConfigWith(dir, "  policy:", "  policy: greedy");
  const auto p = RunCli("explore --config " + bad_policy.string() + " --out " +
                        (dir / "out").string());
  EXPECT_EQ(p.exit_code, 2) << p.output;
  EXPECT_NE(p.output.find("selection.policy"), std::string::npos) << p.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// Lines of `text` (the csv's rows, header included).
int CountLines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

TEST(Explore, CompareWritesOneRowPerPolicyAndSeed) {
  const fs::path dir = FreshDir("explore_compare");
  const fs::path config = ConfigWith(dir, "max_time_s:", "max_time_s: 15.0");
  const auto r = RunCli("explore --compare --config " + config.string() +
                        " --policies all,covariance --seeds 4-5 --out " + (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* file : {"compare.md", "compare.csv", "metrics.json", "slam_time.png",
                           "nees.png", "map_all.png", "map_covariance.png"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  }
  const std::string csv = ReadText(dir / "out" / "compare.csv");
  EXPECT_EQ(CountLines(csv), 1 + 2 * 2) << csv;
  EXPECT_NE(csv.find("\ncovariance,5,"), std::string::npos) << csv;
  const auto m = nlohmann::json::parse(ReadText(dir / "out" / "metrics.json"));
  for (const char* key : {"params", "command", "policies", "seeds", "summary", "savings", "runs",
                          "wall_time_s"}) {
    EXPECT_TRUE(m.contains(key)) << key;
  }
  ASSERT_EQ(m["summary"].size(), 2u);
  for (const char* key : {"slam_time_total_s", "slam_time_max_mean_s", "slam_time_max_s",
                          "open_loop_time_s", "accuracy_step_mean", "accuracy_run_mean", "anees",
                          "anees_band", "anees_in_band", "anees_mean", "mean_error_m",
                          "final_error_m", "odometry_mean_error_m", "lines", "corners", "steps",
                          "elapsed_s"}) {
    EXPECT_TRUE(m["summary"][1].contains(key)) << key;
  }
  EXPECT_EQ(m["runs"].size(), 4u);
  EXPECT_EQ(m["savings"][0]["against"], "all");
  const std::string md = ReadText(dir / "out" / "compare.md");
  EXPECT_NE(md.find("| covariance | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("covariance vs all:"), std::string::npos) << md;
}

TEST(Explore, CompareRejectsBadSeedsAndPolicies) {
  const fs::path dir = FreshDir("explore_compare_errors");
  const fs::path config = ConfigWith(dir, "max_time_s:", "max_time_s: 5.0");
  const std::string head = "explore --compare --config " + config.string() + " --out " +
                           (dir / "out").string();
  for (const char* bad : {"5-2", "x", "1,,2"}) {
    const auto r = RunCli(head + " --seeds " + bad);
    EXPECT_EQ(r.exit_code, 2) << bad << r.output;
    EXPECT_NE(r.output.find("--seeds"), std::string::npos) << r.output;
  }
  for (const char* bad : {"all,greedy", "all,all", ""}) {
    const auto r = RunCli(head + " --policies '" + bad + "'");
    EXPECT_EQ(r.exit_code, 2) << bad << r.output;
    EXPECT_NE(r.output.find("--policies"), std::string::npos) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "out"));
  const auto without = RunCli("explore --config " + config.string() + " --seeds 1-2 --out " +
                              (dir / "out").string());
  EXPECT_EQ(without.exit_code, 2) << without.output;  // --seeds needs --compare
}

}  // namespace
}  // namespace slamkit
