#include "slamkit/runners/features/exploration_config.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "common/temp_dir.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

// configs/*_selection.yaml are exploration experiments; each loads, and its world exists.
TEST(ExplorationConfig, TheShippedExperimentsLoad) {
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(SLAMKIT_SOURCE_DIR) / "configs")) {
    if (!entry.path().stem().string().ends_with("_selection")) continue;
    SCOPED_TRACE(entry.path().string());
    const ExplorationConfig c = LoadExplorationConfig(entry.path());
    EXPECT_TRUE(fs::exists(c.world)) << c.world;
    EXPECT_EQ(c.slam.sigma_v_mps, c.run.sigma_v_mps);  // the prediction is told the noise
    ++loaded;
  }
  EXPECT_GE(loaded, 1);
}

class ExplorationConfigFile : public testing::TempDirTest {};

TEST_F(ExplorationConfigFile, KeysAreReadAndMistakesNamed) {
  const ExplorationConfig c = LoadExplorationConfig(WriteFile(
      "e.yaml", "world: plan.txt\nstart: [1, 2, 0.5]\nselection: {policy: entropy, k_max: 4}\n"
                "timing: wall\nlaser: {range_m: 8}\n"));
  EXPECT_EQ(c.world.filename(), "plan.txt");
  EXPECT_EQ(c.start.y(), 2.0);
  EXPECT_EQ(c.slam.selection, SelectionKind::kEntropy);
  EXPECT_EQ(c.slam.covariance.k_max, 4);
  EXPECT_EQ(c.run.timing, SlamTiming::kWallClock);
  EXPECT_EQ(c.run.laser.max_range_m, 8.0);  // no-return beams read the range used
  struct Case {
    std::string yaml, part;
  };
  const Case cases[] = {
      {"start: [1, 2, 0.5]\n", "key 'world'"},
      {"world: p.txt\nstart: [1, 2]\n", "e.yaml:2: key 'start'"},
      {"world: p.txt\nmax_time_s: -1\n", "key 'max_time_s': must be > 0"},
      {"world: p.txt\nselection: {policy: greedy}\n", "selection.policy"},
      {"world: p.txt\nlaser: {bems: 3}\n", "bems"},
  };
  for (const Case& k : cases) {
    try {
      LoadExplorationConfig(WriteFile("e.yaml", k.yaml));
      ADD_FAILURE() << "no error for " << k.yaml;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(k.part), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace slamkit
