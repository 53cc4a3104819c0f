// `slamkit mc --shard K/N` and `slamkit merge` (issue 31 part 5): the shards of a study, merged,
// give the unsharded run's outputs; shards that do not make one study are refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit::testing {
namespace {

namespace fs = std::filesystem;

std::string Config(const std::string& name) {
  return std::string(SLAMKIT_SOURCE_DIR) + "/configs/" + name;
}

std::string Text(const fs::path& path) {
  std::ostringstream text;
  text << std::ifstream(path).rdbuf();
  return text.str();
}

// metrics.json without the wall times, which differ from run to run.
nlohmann::json WithoutTimes(const fs::path& dir) {
  nlohmann::json m = nlohmann::json::parse(std::ifstream(dir / "metrics.json"));
  m.erase("step_time_mean_s");
  m.erase("step_time_max_s");
  for (nlohmann::json& run : m["per_run"]) {
    run.erase("step_time_mean_s");
    run.erase("step_time_max_s");
  }
  return m;
}

// `mc ARGS` whole and in `count` shards merged (given last to first): the same outputs.
void ExpectShardsMergeToTheWholeRun(const std::string& name, const std::string& args, int count) {
  const fs::path dir = FreshDir("merge_" + name);
  const std::string mc = "mc " + args + " --no-figures --out ";
  ASSERT_EQ(RunCli(mc + (dir / "whole").string()).exit_code, 0);
  std::string shards;
  for (int k = count; k >= 1; --k) {
    const fs::path shard = dir / ("shard" + std::to_string(k));
    const CliResult r = RunCli(mc + shard.string() + " --shard " + std::to_string(k) + "/" +
                               std::to_string(count));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    shards += " " + shard.string();
  }
  const CliResult merged = RunCli("merge" + shards + " --no-figures --out " + (dir / "merged").string());
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  const nlohmann::json whole = WithoutTimes(dir / "whole");
  EXPECT_EQ(whole, WithoutTimes(dir / "merged")) << name;
  EXPECT_EQ(Text(dir / "whole" / "consistency.csv"), Text(dir / "merged" / "consistency.csv"));
  EXPECT_EQ(Text(dir / "whole" / "world.csv"), Text(dir / "merged" / "world.csv"));
  const int runs = whole["runs"].get<int>();
  for (int k = 0; k < runs; ++k) {
    const fs::path run = fs::path("run_" + std::to_string(k)) / "errors.csv";
    EXPECT_EQ(Text(dir / "whole" / run), Text(dir / "merged" / run)) << run;
  }
  // A shard alone is a study of its runs: its figures are not the whole run's.
  const nlohmann::json first = WithoutTimes(dir / "shard1");
  EXPECT_EQ(first["shard"]["index"], 1);
  EXPECT_EQ(first["per_run"].size(), static_cast<std::size_t>(runs / count));
  EXPECT_NE(first["anees"], whole["anees"]);
}

TEST(MergeCli, FourShardsOfTheRouteGiveTheWholeRun) {
  ExpectShardsMergeToTheWholeRun("route", "--config " + Config("short.yaml") + " --runs 12", 4);
}

// SWSLAM's runs differ in length and carry per-section figures: both merge exactly too.
TEST(MergeCli, ShardsOfSwslamRunsKeepTheirSectionMeans) {
  ExpectShardsMergeToTheWholeRun("swslam", "--config " + Config("swslam.yaml") + " --runs 4", 2);
}

TEST(MergeCli, ShardsThatAreNotOneStudyAreRefused) {
  const fs::path dir = FreshDir("merge_refused");
  const std::string mc = "mc --config " + Config("short.yaml") + " --runs 6 --no-figures ";
  const auto shard = [&](const std::string& name, const std::string& extra) {
    const CliResult r = RunCli(mc + extra + " --out " + (dir / name).string());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return " " + (dir / name).string();
  };
  const std::string s1 = shard("s1", "--shard 1/3"), s2 = shard("s2", "--shard 2/3");
  const std::string s3_seed2 = shard("s3_seed2", "--shard 3/3 --seed 2");
  const std::string whole = shard("whole", "");
  const auto merge = [&](const std::string& shards) {
    return RunCli("merge" + shards + " --out " + (dir / "merged").string());
  };
  const CliResult missing = merge(s1 + s2);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("shard 3/3 is missing"), std::string::npos) << missing.output;
  const CliResult seed = merge(s1 + s2 + s3_seed2);
  EXPECT_EQ(seed.exit_code, 2);
  EXPECT_NE(seed.output.find("'seed' differs"), std::string::npos) << seed.output;
  const CliResult twice = merge(s1 + s1 + s2);
  EXPECT_EQ(twice.exit_code, 2);
  EXPECT_NE(twice.output.find("given twice"), std::string::npos) << twice.output;
  const CliResult unsharded = merge(whole);
  EXPECT_EQ(unsharded.exit_code, 2);
  EXPECT_NE(unsharded.output.find("not the output of slamkit mc --shard"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "merged"));
  for (const char* bad : {"4/3", "0/3", "two"}) {
    const CliResult r = RunCli(mc + "--shard " + bad + " --out " + (dir / "bad").string());
    EXPECT_EQ(r.exit_code, 2) << bad;
    EXPECT_NE(r.output.find("--shard"), std::string::npos) << r.output;
  }
  const CliResult too_many = RunCli(mc + "--shard 1/7 --out " + (dir / "bad").string());
  EXPECT_EQ(too_many.exit_code, 2);
  EXPECT_NE(too_many.output.find("at most --runs"), std::string::npos) << too_many.output;
  EXPECT_FALSE(fs::exists(dir / "bad"));
}

}  // namespace
}  // namespace slamkit::testing
