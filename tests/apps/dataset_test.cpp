// End-to-end runs on the real data sets in ../shared/datasets (read in place, never copied).
#include <gtest/gtest.h>

#include <filesystem>

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

}  // namespace
}  // namespace slamkit
