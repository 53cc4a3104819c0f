// `slamkit coop` end to end: the output contract on MRCLAM and the simulated vessels, and its
// errors on bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kDataset6 = fs::path(SLAMKIT_DATASETS_DIR) / "mrclam" / "MRCLAM_Dataset6";
const std::string kConfigs = std::string(SLAMKIT_SOURCE_DIR) + "/configs/";

nlohmann::json Metrics(const fs::path& dir) {
  return nlohmann::json::parse(std::ifstream(dir / "metrics.json"));
}

// A minute of the five robots with every mode: each mode's files and keys, the batch mode's
// covariance-free figures, and every estimate aligned no worse than it is raw.
TEST(CoopCli, AnMrclamMinuteWritesEveryModeItsFiles) {
  if (!fs::exists(kDataset6 / "Barcodes.dat")) GTEST_SKIP() << "no " << kDataset6;
  const fs::path dir = FreshDir("coop_mrclam");
  const CliResult r = RunCli("coop --mrclam " + kDataset6.string() + " --config " + kConfigs +
                             "mrclam.yaml --duration 60 --no-figures --out " + dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("aligned [m]"), std::string::npos) << r.output;
  const nlohmann::json m = Metrics(dir);
  for (const char* mode :
       {"dead-reckoning", "mono", "eo", "eo-exact", "central", "mono-smoothed"}) {
    ASSERT_TRUE(m["modes"].contains(mode)) << mode;
    const nlohmann::json& vehicles = m["modes"][mode]["vehicles"];
    ASSERT_EQ(vehicles.size(), 5u) << mode;
    for (const nlohmann::json& v : vehicles) {
      EXPECT_LE(v["position_rmse_aligned_m"].get<double>(),
                v["position_rmse_m"].get<double>() + 1e-12)
          << mode;
    }
    EXPECT_TRUE(fs::exists(dir / mode / "trajectory_4.tum")) << mode;
  }
  const nlohmann::json& smoothed = m["modes"]["mono-smoothed"];
  EXPECT_TRUE(smoothed["vehicles"][0]["anees"].is_null());
  EXPECT_FALSE(smoothed["vehicles"][0].contains("improvement_ratio_mean_pct"));
  EXPECT_GT(smoothed["landmark_updates"].get<int>(), 0);
  EXPECT_TRUE(fs::exists(dir / "mono-smoothed" / "map_0.csv"));
  EXPECT_FALSE(fs::exists(dir / "dead-reckoning" / "map_0.csv"));
}

// One named mode on the simulated vessels runs that mode alone.
TEST(CoopCli, OneModeOnTheVesselsIsAllItRuns) {
  const fs::path dir = FreshDir("coop_marine");
  const CliResult r = RunCli("coop --config " + kConfigs +
                             "marine_eo.yaml --runs 2 --mode mono-smoothed --no-figures --out " +
                             dir.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json m = Metrics(dir);
  ASSERT_EQ(m["modes"].size(), 1u);
  EXPECT_EQ(m["runs"].get<int>(), 2);
  EXPECT_EQ(m["modes"]["mono-smoothed"]["vehicles"].size(), 2u);
}

// A folder without the data set's files, and a mode that does not exist: exit 2, the culprit
// named, and no output directory.
TEST(CoopCli, BadInputIsRefusedWithoutOutput) {
  const fs::path dir = FreshDir("coop_bad");
  const fs::path empty = dir / "not_mrclam";
  fs::create_directories(empty);
  const fs::path out = dir / "out";
  const CliResult no_data = RunCli("coop --mrclam " + empty.string() + " --config " + kConfigs +
                                   "mrclam.yaml --out " + out.string());
  EXPECT_EQ(no_data.exit_code, 2) << no_data.output;
  EXPECT_NE(no_data.output.find("not_mrclam"), std::string::npos) << no_data.output;
  EXPECT_FALSE(fs::exists(out));
  const CliResult bad_mode = RunCli("coop --config " + kConfigs +
                                    "marine_eo.yaml --mode smoothed --out " + out.string());
  EXPECT_EQ(bad_mode.exit_code, 2) << bad_mode.output;
  EXPECT_NE(bad_mode.output.find("--mode"), std::string::npos) << bad_mode.output;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace slamkit::testing
