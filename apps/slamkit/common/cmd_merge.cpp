// `slamkit merge`: the output folders of `slamkit mc --shard K/N` joined into the unsharded run's.
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common/commands.hpp"
#include "landmark/mc_figures.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "grid/suite_sheet.hpp"
#include "slamkit/core/angle.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/json_reader.hpp"
#include "slamkit/io/landmark_csv.hpp"
#include "slamkit/runners/grid/suite_merge.hpp"
#include "slamkit/runners/landmark/monte_carlo_merge.hpp"
#include "slamkit/runners/landmark/outputs.hpp"

namespace slamkit::app {
namespace {

namespace fs = std::filesystem;

struct MergeOptions {
  std::vector<std::string> shards;
  std::string out;
  bool no_figures = false;
};

// A shard folder: its metrics.json and each run's errors.csv.
SavedMonteCarloShard ReadShard(const std::string& dir) {
  const fs::path metrics_path = fs::path(dir) / "metrics.json";
  SavedMonteCarloShard shard;
  shard.name = dir;
  shard.metrics = ReadJson(metrics_path);
  if (!shard.metrics.is_object() || !shard.metrics.contains("shard") ||
      !shard.metrics.contains("per_run")) {
    throw InputError(metrics_path.string() +
                     ": no 'shard' or 'per_run': not the output of slamkit mc --shard K/N");
  }
  try {
    for (const nlohmann::json& entry : shard.metrics.at("per_run")) {
      const fs::path errors = fs::path(dir) / fmt::format("run_{}", entry.at("run").get<int>()) /
                              "errors.csv";
      shard.runs.push_back({entry, ReadRunErrorsCsv(errors)});
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: per_run: {}", metrics_path.string(), e.what()));
  }
  shard.metrics.erase("per_run");
  return shard;
}

MergedMonteCarlo Merge(const std::vector<SavedMonteCarloShard>& shards) {
  LandmarkWorld world = ReadLandmarkCsv(fs::path(shards.front().name) / "world.csv");
  try {
    return MergeMonteCarloShards(shards, std::move(world));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("merge: a shard's metrics.json lacks a key or has a wrong "
                                 "type: {}", e.what()));
  }
}

// A `slamkit suite --shard` output: summary.json and no metrics.json.
bool IsSuiteOutput(const fs::path& dir) {
  return fs::exists(dir / "summary.json") && !fs::exists(dir / "metrics.json");
}

MergedSuite MergeSuites(const std::vector<std::string>& dirs) {
  std::vector<SavedSuiteShard> shards;
  for (const std::string& dir : dirs) {
    const fs::path path = fs::path(dir) / "summary.json";
    if (!IsSuiteOutput(dir)) throw InputError(dir + ": not a suite output (mixed with mc shards?)");
    shards.push_back({dir, ReadJson(path)});
    if (!shards.back().summary.contains("shard")) {
      throw InputError(path.string() + ": no 'shard': not the output of slamkit suite --shard K/N");
    }
  }
  try {
    return MergeSuiteShards(shards);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("merge: a shard's summary.json lacks a key or has a wrong "
                                 "type: {}", e.what()));
  }
}

// The suite's shards: their runs' folders copied, the summary and contact sheet of all of them.
int RunSuiteMerge(const MergeOptions& o) {
  const MergedSuite merged = MergeSuites(o.shards);
  OutputDir output(o.out);
  const fs::path& dir = output.staging();
  for (const std::string& shard : o.shards) {
    if (fs::exists(fs::path(shard) / "runs")) {
      fs::copy(fs::path(shard) / "runs", dir / "runs", fs::copy_options::recursive);
    }
  }
  const std::string title = "slamkit suite: " + merged.study.value("manifest", std::string());
  if (!o.no_figures) WriteSuiteContactSheet(dir, merged.records, title);
  WriteSuiteSummary(dir, title, merged.records);
  output.Commit();
  int failed = 0;
  for (const SuiteRunRecord& r : merged.records) failed += r.failure.empty() ? 0 : 1;
  fmt::print("merged {} suite shards: {} runs, {} failed\nwrote {}\n", o.shards.size(),
             merged.records.size(), failed, o.out);
  return failed > 0 ? 1 : 0;
}

int RunMergeCommand(const MergeOptions& o) {
  if (IsSuiteOutput(o.shards.front())) return RunSuiteMerge(o);
  std::vector<SavedMonteCarloShard> shards;
  for (const std::string& dir : o.shards) shards.push_back(ReadShard(dir));
  const MergedMonteCarlo merged = Merge(shards);
  OutputDir output(o.out);
  const fs::path& dir = output.staging();
  MonteCarloWriter writer(dir);
  for (const SavedMonteCarloShard& shard : shards) {
    for (const SavedMonteCarloRun& run : shard.runs) {
      const std::string name = fmt::format("run_{}", run.entry.at("run").get<int>());
      fs::copy(fs::path(shard.name) / name, dir / name, fs::copy_options::recursive);
    }
    const bool has_run_0 = shard.metrics.at("shard").at("first_run").get<int>() == 0;
    if (has_run_0 && !o.no_figures && fs::exists(fs::path(shard.name) / "map.png")) {
      fs::copy_file(fs::path(shard.name) / "map.png", dir / "map.png");
    }
  }
  for (const nlohmann::json& entry : merged.per_run) writer.AddEntry(entry);
  const std::string scenario = merged.metrics.value("scenario", std::string("study"));
  if (!o.no_figures) WriteConsistencyPng(dir, scenario, merged.mc);
  writer.Finish(merged.metrics, merged.mc);  // metrics.json last
  output.Commit();
  fmt::print("merged {} shards of {}: {} runs\n", shards.size(), scenario, merged.mc.run_count);
  fmt::print("  {:<28}{:>14.4f}\n", "position RMSE [m]", merged.mc.rmse.position_m);
  fmt::print("  {:<28}{:>14.4f}\n", "heading RMSE [deg]", RadToDeg(merged.mc.rmse.heading_rad));
  fmt::print("  {:<28}{:>14.3f}   95% band [{:.3f}, {:.3f}]\n", "ANEES", merged.mc.anees_mean,
             merged.mc.band.lo, merged.mc.band.hi);
  fmt::print("wrote {}\n", o.out);
  return 0;
}

}  // namespace

void RegisterMerge(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<MergeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "merge", "the output folders of `slamkit mc --shard K/N` or `slamkit suite --shard K/N` "
               "(K = 1..N, in any order) joined into the unsharded run's: the same metrics.json "
               "or summary.json (times and memory aside) and run folders");
  AddExamples(cmd, {"out/default_1 out/default_2 --out out/default_merged   # after both "
                    "examples of slamkit mc --help"});
  cmd->add_option("shards", o->shards, "the shard output folders")
      ->required()
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--out", o->out, "output directory")->required();
  cmd->add_flag("--no-figures", o->no_figures, "skip the PNG figures");
  cmd->callback([o, &exit_code] { exit_code = RunMergeCommand(*o); });
}

}  // namespace slamkit::app
