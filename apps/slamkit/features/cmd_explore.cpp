// `slamkit explore`: the active loop of SPEC S1 (frontier exploration driven by the
// line-and-corner EKF-SLAM) on a simulated robot in a floor plan, compared with the truth.
#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "features/explore_figures.hpp"
#include "features/feature_outputs.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "common/progress.hpp"
#include "slamkit/io/atomic_file.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/floor_plan_reader.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/report/figures.hpp"
#include "slamkit/runners/features/explore_compare.hpp"
#include "slamkit/runners/features/explore_run.hpp"

namespace slamkit::app {
namespace {

struct ExploreOptions {
  std::string config;
  std::string out;
  std::string policy;  // overrides the config's selection.policy
  std::optional<std::uint64_t> seed;
  bool compare = false;  // every policy of `policies` on every seed of `seeds`
  std::string policies = "all,entropy,covariance";
  std::string seeds = "1-20";
};

// "all,entropy" as the list of policies; InputError naming --policies for an unknown or
// repeated one.
std::vector<SelectionKind> ParsePolicies(const std::string& text) {
  std::vector<SelectionKind> policies;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, comma - start);
    try {
      policies.push_back(SelectionKindOf(name));
    } catch (const std::invalid_argument& e) {
      throw InputError(fmt::format("--policies '{}': {}", text, e.what()));
    }
    if (std::count(policies.begin(), policies.end(), policies.back()) > 1) {
      throw InputError(fmt::format("--policies '{}': '{}' is given twice", text, name));
    }
    start = comma + 1;
  }
  return policies;
}

// `explore --compare`: the runs, then the table, the runs' rows, metrics.json and the figures.
int RunCompareCommand(const ExploreOptions& o) {
  ExploreCompareParams params;
  params.policies = ParsePolicies(o.policies);
  params.seeds = ParseSeeds(o.seeds);
  const ExplorationConfig config = LoadExplorationConfig(o.config);
  const FloorPlan plan{ReadFloorPlanFile(config.world)};
  OutputDir output(o.out);
  const std::string command =
      fmt::format("slamkit explore --compare --config {} --policies {} --seeds {} --out {}",
                  o.config, o.policies, o.seeds, o.out);
  Progress progress("runs", static_cast<int>(params.policies.size() * params.seeds.size()));
  const ExploreCompareResult result = RunExploreCompare(
      plan, config, params, [&progress](int done, int /*total*/) { progress.Update(done); });
  WriteExploreCompareOutputs(output.staging(), result, config, params, command);
  WriteCompareFigures(output.staging(), plan, result, params.seeds.front());
  output.Commit();
  fmt::print("{}wrote {}\n", ExploreCompareMarkdown(result, config, command), o.out);
  return 0;
}

int RunExploreCommand(const ExploreOptions& o) {
  if (o.compare) return RunCompareCommand(o);
  ExplorationConfig config = LoadExplorationConfig(o.config);
  if (!o.policy.empty()) config.slam.selection = SelectionKindOf(o.policy);
  if (o.seed) config.seed = *o.seed;
  const FloorPlan plan{ReadFloorPlanFile(config.world)};
  OutputDir output(o.out);
  const ExploreResult result = RunFeatureExploration(plan, config);
  const std::filesystem::path& dir = output.staging();
  WriteTumTrajectory(dir / "trajectory.tum", result.run.estimate);
  WriteTumTrajectory(dir / "truth.tum", result.run.truth);
  WriteTumTrajectory(dir / "odometry.tum", result.run.odometry);
  WriteLinesCsv(dir / "lines.csv", result.lines);
  WriteJson(dir / "metrics.json", ExploreMetrics(result, config));
  WriteLineMapFigure(dir / "map.png",
                     LineMapOf(plan, result,
                               fmt::format("explore: {} policy, seed {}",
                                           SelectionKindName(config.slam.selection), config.seed)));
  output.Commit();
  const ExploreFigures f = ExploreFiguresOf(result);
  fmt::print("{} steps, {:.1f} s simulated ({}): SLAM time {:.4f} s (max {:.6f}), open-loop {:.1f} s\n",
             f.steps, f.elapsed_s, ExplorerModeName(f.final_mode), f.slam_time_total_s,
             f.slam_time_max_s, f.open_loop_time_s);
  fmt::print("mean error {:.3f} m (odometry {:.3f} m), mean pose NEES {:.2f}, {} lines, {} corners\n",
             f.mean_error_m, f.odometry_mean_error_m, f.mean_nees, f.lines, f.corners);
  fmt::print("wrote {}\n", o.out);
  return 0;
}

}  // namespace

void RegisterExplore(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<ExploreOptions>();
  CLI::App* cmd = app.add_subcommand(
      "explore", "frontier exploration driven by line-and-corner EKF-SLAM in a floor plan (SPEC S1)");
  AddExamples(cmd, {
               "--config configs/office_selection.yaml --policy entropy --out out/office"});
  cmd->add_option("--config", o->config, "the experiment (configs/office_selection.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "output directory")->required();
  CLI::Option* compare = cmd->add_flag(
      "--compare", o->compare, "compare the policies of --policies over the seeds of --seeds");
  cmd->add_option("--policies", o->policies, "with --compare: all,entropy,entropy-fast,covariance")
      ->capture_default_str()
      ->needs(compare);
  cmd->add_option("--seeds", o->seeds, "with --compare: seeds, 1-20, 1,3,7 or 2")
      ->capture_default_str()
      ->needs(compare);
  CLI::Option* policy = cmd->add_option("--policy", o->policy, "all | entropy | entropy-fast | covariance (default: the config's)")
      ->check(CLI::IsMember({"all", "entropy", "entropy-fast", "covariance"}));
  cmd->add_option("--seed", o->seed, "the run's random seed (default: the config's)")
      ->check(SeedNumber())
      ->excludes(compare);
  policy->excludes(compare);
  cmd->callback([o, &exit_code] { exit_code = RunExploreCommand(*o); });
}

}  // namespace slamkit::app
