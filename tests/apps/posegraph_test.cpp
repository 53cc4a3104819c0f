// `slamkit posegraph` end to end: a small loop written here, and the real Intel graph.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit::testing {
namespace {

namespace fs = std::filesystem;

// A square of four poses whose closing edge disagrees with the others by 0.1 m.
fs::path WriteSquare(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream f(dir / "square.g2o");
  for (int i = 0; i < 4; ++i) f << "VERTEX_SE2 " << i << " 0 0 0\n";
  for (int i = 0; i < 4; ++i) {
    f << "EDGE_SE2 " << i << " " << (i + 1) % 4 << (i == 3 ? " 1.1" : " 1") << " 0 1.5707963267948966"
      << " 1 0 0 1 0 100000000\n";  // headings held: the optimum is linear
  }
  return dir / "square.g2o";
}

TEST(PoseGraphCli, OptimisesFromBothStartsAndWritesItsOutputs) {
  const fs::path dir = FreshDir("posegraph");
  const fs::path out = dir / "out";
  const CliResult r = RunCli("posegraph " + WriteSquare(dir).string() + " --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* name : {"graph.g2o", "trajectory.tum", "trajectory_file.tum",
                           "trajectory_chordal.tum", "metrics.json", "graph.png"}) {
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  const nlohmann::json m = nlohmann::json::parse(std::ifstream(out / "metrics.json"));
  EXPECT_EQ(m["vertices"], 4);
  EXPECT_EQ(m["edges"], 4);
  // The 0.1 m misclosure spread over four unit-information edges: χ² = 4 (0.1 / 4)².
  EXPECT_NEAR(m["starts"]["chordal"]["chi2"].get<double>(), 4 * 0.025 * 0.025, 1e-6);
  EXPECT_LT(m["starts"]["chordal"]["chi2"].get<double>(),
            m["starts"]["chordal"]["initial_chi2"].get<double>());
}

TEST(PoseGraphCli, AMalformedFileIsAnInputErrorNamingTheLine) {
  const fs::path dir = FreshDir("posegraph_bad");
  std::ofstream(dir / "bad.g2o") << "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n"
                                 << "EDGE_SE2 0 1 1 0 zero 1 0 0 1 0 1\n";
  const CliResult r =
      RunCli("posegraph " + (dir / "bad.g2o").string() + " --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("bad.g2o:3"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

// SE-Sync's certified optimum of intel.g2o is 52.35 (Rosen et al. 2019, Table 1).
TEST(PoseGraphCli, IntelReachesSeSyncsCertifiedOptimum) {
  const fs::path intel = fs::path(SLAMKIT_DATASETS_DIR) / "posegraphs" / "intel.g2o";
  if (!fs::exists(intel)) GTEST_SKIP() << "no " << intel;
  const fs::path out = FreshDir("posegraph_intel") / "out";
  const CliResult r = RunCli("posegraph " + intel.string() + " --objective sesync --no-figures --out " +
                             out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json m = nlohmann::json::parse(std::ifstream(out / "metrics.json"));
  EXPECT_NEAR(m["starts"]["chordal"]["sesync_objective"].get<double>(), 52.35, 0.005);
  EXPECT_EQ(m["best"], "chordal");
}

}  // namespace
}  // namespace slamkit::testing
