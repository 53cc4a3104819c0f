// `slamkit features` end to end: on the real logs of ../shared/datasets/carmen (read in place),
// and its input errors.
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

const std::string kCarmen = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/";

// The first part of Intel, one loop of its corridors: the line map must hold the relations far
// better than the odometry it starts from, and every file of the contract is written.
TEST(Features, IntelPrefixBeatsTheOdometryAndWritesTheContractFiles) {
  if (!fs::exists(kCarmen + "intel.clf")) GTEST_SKIP() << "no intel.clf";
  const fs::path dir = FreshDir("features_intel");
  const auto r = RunCli("features --log " + kCarmen + "intel.clf --relations " + kCarmen +
                        "intel.relations --max-scans 3000 --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto m = nlohmann::json::parse(ReadText(dir / "metrics.json"));
  EXPECT_EQ(m["scans"], 3000);
  EXPECT_EQ(m["selection"], "covariance");
  EXPECT_GT(m["relations"].get<int>(), 100);
  EXPECT_LT(m["relations_trans_mean_m"].get<double>(),
            0.25 * m["odometry_relations_trans_mean_m"].get<double>());
  EXPECT_LT(m["relations_rot_mean_deg"].get<double>(),
            0.25 * m["odometry_relations_rot_mean_deg"].get<double>());
  EXPECT_GT(m["lines"].get<int>(), 20);
  const double accuracy = m["accuracy_ratio_mean"].get<double>();
  EXPECT_GT(accuracy, 0.5);
  EXPECT_LE(accuracy, 1.0);
  EXPECT_LE(m["applied_per_update"].get<double>(), 3.0);  // k_max
  for (const char* key : {"wall_time_s", "correction_time_s", "correction_time_max_s",
                          "modelled_time_s", "line_sightings", "corner_sightings", "params",
                          "peak_rss_mib"}) {
    EXPECT_TRUE(m.contains(key)) << key;
  }
  const std::string trajectory = ReadText(dir / "trajectory.txt");
  EXPECT_EQ(std::count(trajectory.begin(), trajectory.end(), '\n'), 3000);
  const std::string lines = ReadText(dir / "lines.csv");
  EXPECT_EQ(std::count(lines.begin(), lines.end(), '\n'), m["lines"].get<int>() + 1);
  for (const char* file : {"trajectory.tum", "odometry.tum", "map.png"}) {
    EXPECT_TRUE(fs::exists(dir / file)) << file;
  }
}

// CSAIL with its raw odometry against the per-scan reference, paired by index; each policy runs.
TEST(Features, CsailBeatsItsRawOdometryWithEveryPolicy) {
  if (!fs::exists(kCarmen + "suite/csail.log.gz")) GTEST_SKIP() << "no suite";
  for (const std::string policy : {"all", "covariance", "entropy-fast"}) {
    const fs::path dir = FreshDir("features_csail_" + policy);
    const auto r = RunCli("features --log " + kCarmen + "suite/csail.log.gz --reference " +
                          kCarmen + "suite/csail.reference.txt --pair-by index --policy " +
                          policy + " --out " + dir.string());
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const auto m = nlohmann::json::parse(ReadText(dir / "metrics.json"));
    EXPECT_EQ(m["selection"], policy);
    EXPECT_LT(m["ate_rmse_m"].get<double>(), 0.5 * m["odometry_ate_rmse_m"].get<double>())
        << policy;
  }
}

TEST(Features, MistakesExitTwoNamingTheFileLineOrOption) {
  if (!fs::exists(kCarmen + "intel.clf")) GTEST_SKIP() << "no intel.clf";
  const fs::path dir = FreshDir("features_bad");
  const fs::path config = dir.parent_path() / "features_bad.yaml";
  std::ofstream(config) << "selection:\n  k_max: 3\nlines:\n  gate: 4\n";
  const std::string log = " --log " + kCarmen + "intel.clf --out " + dir.string();
  auto r = RunCli("features --config " + config.string() + log);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("features_bad.yaml:4"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("unknown key 'gate' in section 'lines'"), std::string::npos)
      << r.output;
  r = RunCli("features --policy best" + log);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--policy"), std::string::npos) << r.output;
  r = RunCli("features --config " + config.string() + " --k-max 2" + log);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_FALSE(fs::exists(dir / "metrics.json"));
}

}  // namespace
}  // namespace slamkit
