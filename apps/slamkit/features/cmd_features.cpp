// `slamkit features`: the line-and-corner EKF-SLAM of SPEC S1 on a CARMEN laser log, its
// odometry as the motion, scored as `slamkit grid` is.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>

#include "common/commands.hpp"
#include "features/feature_outputs.hpp"
#include "common/log_input.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "common/progress.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/runners/features/feature_log_config.hpp"
#include "slamkit/runners/features/feature_log_run.hpp"
#include "slamkit/runners/grid/grid_run.hpp"

namespace slamkit::app {
namespace {

struct FeaturesOptions {
  LogInput input;
  std::string out;
  std::string config;
  std::string policy;  // empty: the config's, else covariance
  bool no_accuracy_ratio = false;
  double odometry_noise = 0.0;  // 0: the default's
  FeatureLogParams params;
};

void WriteFeatureOutputs(const std::filesystem::path& dir, const FeatureLogResult& r,
                         const Trajectory& odometry, const std::string& title) {
  std::filesystem::create_directories(dir);
  WritePoseText(dir / "trajectory.txt", r.trajectory);
  WriteTumTrajectory(dir / "trajectory.tum", WithIncreasingTimes(r.trajectory));
  WriteTumTrajectory(dir / "odometry.tum", WithIncreasingTimes(odometry));
  WriteLinesCsv(dir / "lines.csv", r.lines);
  WriteFeatureMapFigure(dir / "map.png", title, r.lines, r.corners, r.points, r.trajectory);
}

void PrintFeatureRun(const std::string& log, const FeatureLogResult& r, const FeatureLogParams& p) {
  fmt::print("{}: {} scans{}, {} updates, {} lines, {} corners ({})\n", log, r.trajectory.size(),
             r.stopped_early ? " (stopped at max_wall_time_s)" : "", r.updates, r.lines.size(),
             r.corners.size(), SelectionKindName(p.selection));
  fmt::print("  {:<28}{:>12.2f}\n", "wall time [s]", r.wall_time_s);
  fmt::print("  {:<28}{:>12.2f}\n", "correction time [s]", r.correction_time_s);
  fmt::print("  {:<28}{:>12.1f}\n", "peak memory [MiB]", PeakRssMib());
}

int RunFeaturesCommand(FeaturesOptions o) {
  if (!o.config.empty()) {
    const double max_wall_time_s = o.params.max_wall_time_s;
    o.params = LoadFeatureLogConfig(o.config);
    o.params.max_wall_time_s = std::min(o.params.max_wall_time_s, max_wall_time_s);
  }
  if (!o.policy.empty()) o.params.selection = SelectionKindOf(o.policy);
  if (o.no_accuracy_ratio) o.params.accuracy_ratio_every = 0;
  if (o.odometry_noise > 0.0) {
    o.params.odometry_noise = {o.odometry_noise, o.odometry_noise, o.odometry_noise,
                               o.odometry_noise};
  }
  const CarmenLog log = ReadInputLog(o.input);
  std::vector<PoseRelation> relations = ReadInputRelations(o.input);
  const std::optional<Trajectory> reference = LoadReference(o.input, log);
  const Trajectory odometry = OdometryFromOrigin(log);
  OutputDir output(o.out);

  auto progress = std::make_shared<Progress>("scans", static_cast<int>(log.scans.size()));
  const FeatureLogResult result =
      RunFeatureSlamOnLog(log, o.params, [progress](int done, int) { progress->Update(done); });
  const LogEvaluation eval =
      EvaluateOnLog(result.trajectory, odometry, std::move(relations), reference,
                    ScoringOf(o.input));
  nlohmann::json metrics =
      FeatureLogMetrics(result, o.params, eval.relations ? &*eval.relations : nullptr,
                        eval.reference ? &*eval.reference : nullptr);
  metrics["version"] = SLAMKIT_VERSION;
  metrics["peak_rss_mib"] = PeakRssMib();
  AddLogInputMetrics(o.input, log, eval, metrics);

  const std::filesystem::path& dir = output.staging();
  WriteFeatureOutputs(dir, result, odometry, std::filesystem::path(o.input.source()).filename());
  WriteJson(dir / "metrics.json", metrics);
  PrintFeatureRun(o.input.source(), result, o.params);
  if (eval.relations) PrintRelations(*eval.relations);
  output.Commit();
  return ReportEvaluation(o.input, eval, o.out);
}

// The filter's options, which --config replaces (--policy and the run's options apply to both).
std::vector<CLI::Option*> AddFilterOptions(CLI::App* cmd, FeaturesOptions& o) {
  FeatureLogParams& p = o.params;
  std::vector<CLI::Option*> options;
  options.push_back(
      cmd->add_option("--k-max", p.covariance.k_max, "covariance policy: most updates per scan")
          ->check(NonNegativeNumber())
          ->capture_default_str());
  options.push_back(cmd->add_option("--min-gain", p.entropy.min_gain_nats,
                                    "entropy policies: least information gain "
                                    "to apply an update [nats]")
                        ->check(NonNegativeNumber())
                        ->capture_default_str());
  options.push_back(cmd->add_option("--max-usable-range", p.extraction.max_usable_range_m,
                                    "returns farther than this are not used for features [m]")
                        ->check(PositiveNumber())
                        ->capture_default_str());
  options.push_back(
      cmd->add_option("--odometry-noise", o.odometry_noise,
                      fmt::format("odometry noise, each of srr srt str stt (m/m, m/rad, rad/m, "
                                  "rad/rad) [default: {}]",
                                  p.odometry_noise.srr))
          ->check(PositiveNumber()));
  options.push_back(cmd->add_option("--linear-update", p.linear_update_m,
                                    "process a scan after this much travel [m]")
                        ->check(NonNegativeNumber())
                        ->capture_default_str());
  options.push_back(
      cmd->add_option("--angular-update", p.angular_update_rad, "or after this much turn [rad]")
          ->check(NonNegativeNumber())
          ->capture_default_str());
  return options;
}

void AddRunOptions(CLI::App* cmd, FeaturesOptions& o) {
  cmd->add_option("--policy", o.policy,
                  "selection policy: all, entropy, entropy-fast, covariance "
                  "[default: the "
                  "config's, else covariance]")
      ->check(CLI::IsMember({"all", "entropy", "entropy-fast", "covariance"}));
  cmd->add_option("--max-wall-time", o.params.max_wall_time_s,
                  "stop after this many seconds, keeping what was computed")
      ->check(PositiveNumber());
  cmd->add_flag("--no-accuracy-ratio", o.no_accuracy_ratio,
                "do not run the full update on a copy for the accuracy ratio "
                "(SPEC S1, Eq. 24), "
                "so the times are the policy's alone");
}

}  // namespace

void RegisterFeatures(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<FeaturesOptions>();
  CLI::App* cmd =
      app.add_subcommand("features", "line-and-corner EKF-SLAM (SPEC S1) on a CARMEN laser log");
  AddExamples(cmd, {
               "--log ../shared/datasets/carmen/intel.clf --config configs/features.yaml --relations ../shared/datasets/carmen/intel.relations --out out/intel_features"});
  AddLogInputOptions(cmd, o->input);
  cmd->add_option("--out", o->out, "output directory")->required();
  const std::vector<CLI::Option*> filter_options = AddFilterOptions(cmd, *o);
  CLI::Option* config = cmd->add_option("--config", o->config,
                                        "the filter's parameters from a YAML "
                                        "file (configs/features.yaml), instead "
                                        "of the filter options")
                            ->check(CLI::ExistingFile);
  for (CLI::Option* option : filter_options) config->excludes(option);
  AddRunOptions(cmd, *o);
  cmd->callback([o, &exit_code] { exit_code = RunFeaturesCommand(*o); });
}

}  // namespace slamkit::app
