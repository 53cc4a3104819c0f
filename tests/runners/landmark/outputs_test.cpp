#include "slamkit/runners/landmark/outputs.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>

#include <gtest/gtest.h>

namespace slamkit {
namespace {

namespace fs = std::filesystem;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

MonteCarloResult SmallKeptResult(int runs) {
  ScenarioConfig c = LoadScenario(std::string(SLAMKIT_SOURCE_DIR) + "/configs/short.yaml");
  c.scenario.max_steps = 40;
  MonteCarloParams params;
  params.runs = runs;
  params.threads = 1;
  return RunMonteCarlo(c, params);
}

// Issue 8, item 6: metrics.json's per_run is streamed through a scratch file. The file must
// still be the JSON of the summary keys plus per_run, entry k being run k's summary, and the
// scratch file must not be left behind.
TEST(MonteCarloWriter, MetricsJsonIsTheSummaryPlusEveryRunInOrder) {
  const MonteCarloResult mc = SmallKeptResult(3);
  const fs::path dir = fs::temp_directory_path() / ("slamkit_outputs_" + std::to_string(getpid()));
  fs::remove_all(dir);
  const nlohmann::json summary = {{"runs", 3}, {"anees", mc.anees_mean}};
  WriteMonteCarloOutputs(dir, summary, mc);
  const nlohmann::json metrics = nlohmann::json::parse(ReadText(dir / "metrics.json"));
  EXPECT_EQ(metrics["runs"], 3);
  EXPECT_EQ(metrics["anees"], mc.anees_mean);
  ASSERT_EQ(metrics["per_run"].size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(metrics["per_run"][k], RunSummaryJson(k, mc.summaries[std::size_t(k)])) << k;
  }
  EXPECT_EQ(metrics.size(), 3u);  // runs, anees, per_run
  EXPECT_FALSE(fs::exists(dir / ".per_run.partial"));
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(fs::exists(dir / ("run_" + std::to_string(k)) / "map.csv"));
  fs::remove_all(dir);
}

// Issue 27, part 3: mc's and study's metrics.json echo the scenario through its table, so a
// setting that reaches only FastSLAM (delayed sampling) shows in the output of a run that used it.
TEST(MonteCarloMetrics, EchoesTheScenarioTableWithWhatTheConfigSet) {
  ScenarioConfig c = LoadScenario(std::string(SLAMKIT_SOURCE_DIR) + "/configs/short.yaml");
  c.fastslam.delayed_sampling = !c.fastslam.delayed_sampling;
  c.ekf.association.gate_chi2 = 7.5;
  MonteCarloParams params;
  params.runs = 1;
  const nlohmann::json params_json = MonteCarloMetrics(c, params, MonteCarloResult{})["params"];
  EXPECT_EQ(params_json["fastslam"]["delayed_sampling"], c.fastslam.delayed_sampling);
  EXPECT_EQ(params_json["ekf"]["gate_chi2"], 7.5);
  EXPECT_EQ(params_json["ekf"]["known_association"], c.ekf.known_association());
  EXPECT_EQ(params_json, ScenarioParamsJson(c));
}

TEST(MonteCarloWriter, AnUnfinishedWriterLeavesNoScratchFileAndNoMetrics) {
  const MonteCarloResult mc = SmallKeptResult(1);
  const fs::path dir = fs::temp_directory_path() / ("slamkit_outputs_u" + std::to_string(getpid()));
  fs::remove_all(dir);
  {
    MonteCarloWriter writer(dir);
    writer.Add(0, mc.runs[0], mc.summaries[0]);
    EXPECT_TRUE(fs::exists(dir / ".per_run.partial"));
  }  // as when a run throws before Finish
  EXPECT_FALSE(fs::exists(dir / ".per_run.partial"));
  EXPECT_FALSE(fs::exists(dir / "metrics.json"));
  fs::remove_all(dir);
}

TEST(MonteCarloWriter, AResultWithoutItsRunsIsRefused) {
  MonteCarloResult mc = SmallKeptResult(2);
  mc.runs.clear();
  const fs::path dir = fs::temp_directory_path() / ("slamkit_outputs_r" + std::to_string(getpid()));
  EXPECT_THROW(WriteMonteCarloOutputs(dir, {}, mc), std::invalid_argument);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace slamkit
