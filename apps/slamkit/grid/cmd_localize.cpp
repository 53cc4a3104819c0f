// `slamkit localize`: Monte Carlo localisation of a CARMEN log on a saved map.
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "common/log_input.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "common/progress.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/map_reader.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/report/figures.hpp"
#include "slamkit/runners/localization/localize_run.hpp"

namespace slamkit::app {
namespace {

struct LocalizeOptions {
  LogInput input;
  std::string map;
  std::string config;
  std::string initial_pose;
  bool global = false;
  std::string out;
  LocalizationConfig filter;
};

// "x,y,theta" (m, m, rad) as a pose; InputError naming --initial-pose otherwise.
Pose2 ParsePose(const std::string& text) {
  std::vector<double> v;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ',')) {
    std::size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != part.size() || !std::isfinite(x)) {
      throw InputError("--initial-pose: '" + part + "' is not a finite number (x,y,theta)");
    }
    v.push_back(x);
  }
  if (v.size() != 3) throw InputError("--initial-pose: expected x,y,theta, got '" + text + "'");
  return Pose2(v[0], v[1], v[2]);
}

int RunLocalizeCommand(const LocalizeOptions& o) {
  const LocalizationConfig config =
      o.config.empty() ? o.filter : LoadLocalizationConfig(o.config, o.filter);
  const std::optional<Pose2> initial =
      o.global ? std::nullopt : std::optional<Pose2>(ParsePose(o.initial_pose));
  const OccupancyImage map = ReadOccupancyImage(o.map);
  const CarmenLog log = ReadInputLog(o.input);
  std::vector<PoseRelation> relations = ReadInputRelations(o.input);
  const std::optional<Trajectory> reference = LoadReference(o.input, log);
  OutputDir output(o.out);
  auto progress = std::make_shared<Progress>("scans", static_cast<int>(log.scans.size()));
  const LocalizationResult result = RunLocalization(
      log, map, config, initial, [progress](int done, int) { progress->Update(done); });
  const LogEvaluation eval = EvaluateOnLog(result.trajectory, OdometryTrajectory(log),
                                           std::move(relations), reference, ScoringOf(o.input));
  const std::filesystem::path& dir = output.staging();
  WritePoseText(dir / "trajectory.txt", result.trajectory);
  WriteTumTrajectory(dir / "trajectory.tum", WithIncreasingTimes(result.trajectory));
  // The localised path over the saved map, as `grid` draws its own map (map.png there).
  MapSheetData figure;
  figure.columns = 1;
  figure.panel_px = 1200;
  figure.panels.push_back(
      {std::filesystem::path(o.input.source()).filename().string() + " localised on " +
           std::filesystem::path(o.map).filename().string(),
       map, result.trajectory, {}});
  WriteMapContactSheet(dir / "path.png", figure);
  nlohmann::json metrics =
      LocalizationMetrics(result, config, eval.relations ? &*eval.relations : nullptr,
                          eval.reference ? &*eval.reference : nullptr);
  metrics["version"] = SLAMKIT_VERSION;
  metrics["map"] = o.map;
  metrics["start"] = o.global ? "global" : o.initial_pose;
  if (!o.config.empty()) metrics["config"] = o.config;
  AddLogInputMetrics(o.input, log, eval, metrics);
  WriteJson(dir / "metrics.json", metrics);
  fmt::print("{}: {} scans, {} updates, {:.0f} particles on average, {:.1f} s\n", o.input.source(),
             result.scans, result.updates, result.mean_particles, result.wall_time_s);
  if (result.settled_scan) {
    fmt::print("  converged at scan {} (t = {:.2f} s) and stayed converged\n",
               *result.settled_scan, result.trajectory[*result.settled_scan].t_s);
  } else {
    fmt::print("  not converged at the end of the log (spread above {} m)\n",
               config.mcl.converged_spread_m);
  }
  if (result.last_recovery_scan) {
    fmt::print("  {} updates drew random particles (the scans unlikely), the last at scan {}\n",
               result.recovery_updates, *result.last_recovery_scan);
  }
  if (eval.relations) PrintRelations(*eval.relations);
  output.Commit();
  return ReportEvaluation(o.input, eval, o.out);
}

}  // namespace

void RegisterLocalize(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<LocalizeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "localize", "Monte Carlo localisation (KLD-sampling, likelihood field) of a CARMEN log on "
                  "a saved map (map.yaml, as `slamkit grid` writes it)");
  AddExamples(cmd, {
               "--map out/intel/map.yaml --log ../shared/datasets/carmen/intel.clf --relations ../shared/datasets/carmen/intel.relations --initial-pose 0,0,0 --out out/intel_localize   # after the first grid example",
               "--map out/intel/map.yaml --log ../shared/datasets/carmen/intel.clf --relations ../shared/datasets/carmen/intel.relations --global --out out/intel_global"});
  AddLogInputOptions(cmd, o->input);
  cmd->add_option("--map", o->map, "map_server YAML (image, resolution, origin)")
      ->required()->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "output directory")->required();
  CLI::Option* pose = cmd->add_option("--initial-pose", o->initial_pose,
                                      "start around this pose in the map's frame: x,y,theta "
                                      "(m, m, rad)");
  CLI::Option* global = cmd->add_flag("--global", o->global,
                                      "start with particles over the whole free space");
  pose->excludes(global);
  global->excludes(pose);
  const std::vector<CLI::Option*> filter_options =
      AddParamOptions(cmd, LocalizationParamTable(o->filter));
  CLI::Option* config =
      cmd->add_option("--config", o->config, "the filter's parameters from a YAML file (keys: "
                      "docs/localization.md), instead of the filter options")
          ->check(CLI::ExistingFile);
  for (CLI::Option* option : filter_options) config->excludes(option);
  cmd->callback([o, pose, global, &exit_code] {
    if (pose->count() == 0 && global->count() == 0) {
      throw InputError("localize: give --initial-pose x,y,theta or --global");
    }
    exit_code = RunLocalizeCommand(*o);
  });
}

}  // namespace slamkit::app
