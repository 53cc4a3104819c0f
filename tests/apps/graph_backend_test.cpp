// `slamkit grid --backend graph` and `slamkit suite --backend both` end to end on a real log.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"

namespace slamkit::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kCarmen = fs::path(SLAMKIT_DATASETS_DIR) / "carmen";

std::size_t Lines(const fs::path& path) {
  std::ifstream in(path);
  std::size_t n = 0;
  for (std::string line; std::getline(in, line);) n += line.empty() ? 0 : 1;
  return n;
}

// The first 2,000 Intel scans: every scan gets a pose, the graph is written with a vertex per
// node and an edge per consecutive pair and closure, and the relations beat raw odometry's.
TEST(GraphBackendCli, IntelWritesTheGridOutputsAndTheGraph) {
  if (!fs::exists(kCarmen / "intel.clf")) GTEST_SKIP() << "no intel.clf";
  const fs::path out = FreshDir("graph_backend") / "out";
  const CliResult r = RunCli("grid --log " + (kCarmen / "intel.clf").string() + " --relations " +
                             (kCarmen / "intel.relations").string() +
                             " --backend graph --max-scans 2000 --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("loop closures"), std::string::npos) << r.output;
  for (const char* name : {"trajectory.txt", "trajectory.tum", "map.pgm", "map.yaml", "map.png",
                           "graph.g2o", "metrics.json"}) {
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  EXPECT_EQ(Lines(out / "trajectory.txt"), 2000u);
  const nlohmann::json m = nlohmann::json::parse(std::ifstream(out / "metrics.json"));
  ASSERT_TRUE(m.contains("graph")) << m.dump();
  const int nodes = m["graph"]["nodes"], closures = m["graph"]["loop_closures"];
  EXPECT_GT(nodes, 100);
  EXPECT_GT(closures, 0);
  EXPECT_EQ(m["params"]["backend"], "graph");
  std::size_t vertices = 0, edges = 0;
  std::ifstream graph(out / "graph.g2o");
  for (std::string tag; graph >> tag; graph.ignore(1 << 20, '\n')) {
    vertices += tag == "VERTEX_SE2";
    edges += tag == "EDGE_SE2";
  }
  EXPECT_EQ(vertices, static_cast<std::size_t>(nodes));
  EXPECT_EQ(edges, static_cast<std::size_t>(nodes - 1 + closures));
  EXPECT_LT(m["relations_trans_mean_m"].get<double>(),
            0.2 * m["odometry_relations_trans_mean_m"].get<double>());
}

TEST(GraphBackendCli, PredictionNeedsTheParticleFilter) {
  if (!fs::exists(kCarmen / "intel.clf")) GTEST_SKIP() << "no intel.clf";
  const fs::path out = FreshDir("graph_backend_predict") / "out";
  const CliResult r = RunCli("grid --log " + (kCarmen / "intel.clf").string() +
                             " --backend graph --predict on --max-scans 50 --out " + out.string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--predict on needs the rbpf back end"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
}

// Both back ends on one log: the particle filter per seed, the graph once, the summaries naming
// the graph's run apart.
TEST(GraphBackendCli, SuiteRunsBothBackEndsSideBySide) {
  if (!fs::exists(kCarmen / "intel.clf")) GTEST_SKIP() << "no intel.clf";
  const fs::path dir = FreshDir("graph_backend_suite");
  std::ofstream(dir / "suite.yaml") << "root: " << kCarmen.string() << "\nlogs:\n"
                                    << "  - {name: intel, log: intel.clf, relations: intel.relations}\n";
  const CliResult r = RunCli("suite --manifest " + (dir / "suite.yaml").string() +
                             " --backend both --seeds 1-2 --max-scans 300 --particles 3 --out " +
                             (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("3 runs (1 logs x 2 seeds + 1 graph), 0 failed"), std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "runs" / "intel" / "graph" / "graph.g2o"));
  EXPECT_TRUE(fs::exists(dir / "out" / "runs" / "intel" / "seed_2" / "map.pgm"));
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir / "out" / "summary.json"));
  ASSERT_EQ(summary["logs"].size(), 2u);
  EXPECT_EQ(summary["logs"][0]["backend"], "rbpf");
  EXPECT_EQ(summary["logs"][1]["backend"], "graph");
  EXPECT_EQ(summary["logs"][1]["completed"], 1);
  std::ifstream csv(dir / "out" / "summary.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\nintel (graph),"), std::string::npos) << text;
}

}  // namespace
}  // namespace slamkit::testing
