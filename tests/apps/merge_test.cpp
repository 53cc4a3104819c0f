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
  EXPECT_EQ(ReadText(dir / "whole" / "consistency.csv"), ReadText(dir / "merged" / "consistency.csv"));
  EXPECT_EQ(ReadText(dir / "whole" / "world.csv"), ReadText(dir / "merged" / "world.csv"));
  const int runs = whole["runs"].get<int>();
  for (int k = 0; k < runs; ++k) {
    const fs::path run = fs::path("run_" + std::to_string(k)) / "errors.csv";
    EXPECT_EQ(ReadText(dir / "whole" / run), ReadText(dir / "merged" / run)) << run;
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

// summary.json without what differs from run to run: times and memory.
nlohmann::json SuiteWithoutTimes(const fs::path& dir) {
  nlohmann::json m = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
  for (nlohmann::json& run : m["runs"]) {
    for (const char* key : {"wall_time_s", "peak_rss_mib"}) run.erase(key);
    nlohmann::json& metrics = run["metrics"];
    for (const char* key : {"wall_time_s", "peak_rss_mib", "scans_per_s"}) metrics.erase(key);
    if (metrics.contains("graph")) {
      metrics["graph"].erase("optimization_time_s");
      metrics["graph"].erase("search_time_s");
    }
  }
  for (nlohmann::json& log : m["logs"]) {
    log.erase("wall_time_s");
    log.erase("peak_rss_mib");
  }
  return m;
}

// A suite's log x seed runs (both back ends) in two shards, merged: the unsharded summary and
// every run's folder.
TEST(MergeCli, TwoShardsOfASuiteGiveTheWholeSuite) {
  const std::string carmen = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/suite/edmonton.log.gz";
  if (!fs::exists(carmen)) GTEST_SKIP() << "no suite logs";
  const fs::path dir = FreshDir("merge_suite");
  const std::string suite = "suite --manifest " + Config("carmen_suite.yaml") +
                            " --logs edmonton --seeds 1-2 --backend both --max-scans 10 "
                            "--out ";
  ASSERT_EQ(RunCli(suite + (dir / "whole").string()).exit_code, 0);
  for (const char* k : {"1", "2"}) {  // the runs seed 1, seed 2, graph: one, then two
    const CliResult r = RunCli(suite + (dir / k).string() + " --shard " + k + "/2");
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_NE(r.output.find(std::string(k == std::string("1") ? "1" : "2") + " runs of shard " +
                            k + "/2"), std::string::npos) << r.output;
  }
  const CliResult merged = RunCli("merge " + (dir / "2").string() + " " + (dir / "1").string() +
                                  " --out " + (dir / "merged").string());
  ASSERT_EQ(merged.exit_code, 0) << merged.output;
  const nlohmann::json whole = SuiteWithoutTimes(dir / "whole");
  ASSERT_EQ(whole["runs"].size(), 3u);
  EXPECT_EQ(whole, SuiteWithoutTimes(dir / "merged"));
  for (const char* run : {"edmonton/seed_2", "edmonton/graph"}) {
    const fs::path trajectory = fs::path("runs") / run / "trajectory.tum";
    EXPECT_EQ(ReadText(dir / "whole" / trajectory), ReadText(dir / "merged" / trajectory)) << run;
  }
  EXPECT_TRUE(fs::exists(dir / "merged" / "maps.png"));
  const CliResult missing = RunCli("merge " + (dir / "1").string() + " --out " +
                                   (dir / "missing").string());
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.output.find("shard 2/2 is missing"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace slamkit::testing
