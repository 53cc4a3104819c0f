// `slamkit mc` and `slamkit demo`: Monte Carlo landmark SLAM (EKF-SLAM, FastSLAM 1.0 / 2.0) on a
// simulated scenario.
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "grid_common.hpp"
#include "progress.hpp"
#include "slamkit/core/angle.hpp"
#include "slamkit/core/cpu.hpp"
#include "slamkit/runners/outputs.hpp"
#include "slamkit/runners/scenario_config.hpp"
#include "slamkit/report/figures.hpp"

namespace slamkit::app {
namespace {

struct McOptions {
  std::string config;
  int runs = 50;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string filter = "ekf";  // ekf | fastslam1 | fastslam2
  int particles = FastSlamParams{}.particles;
  std::string out;
  bool no_figures = false;
  bool unknown_association = false;
  bool known_association = false;
};

void PrintSummary(const ScenarioConfig& config, const MonteCarloResult& mc) {
  const ScenarioParams& scenario = config.scenario;
  const AssociationScore& a = mc.association;
  fmt::print("scenario {}: {} runs x {} steps, {} landmarks, {} association\n", scenario.name,
             mc.run_count, mc.t_s.size(), mc.world.landmarks.size(),
             AssociationName(config.ekf.association_method));
  fmt::print("  {:<28}{:>14}\n", "position RMSE [m]", fmt::format("{:.4f}", mc.rmse.position_m));
  fmt::print("  {:<28}{:>14}\n", "heading RMSE [deg]",
             fmt::format("{:.4f}", RadToDeg(mc.rmse.heading_rad)));
  fmt::print("  {:<28}{:>14}   95% band [{:.3f}, {:.3f}], {:.0f}% of steps inside\n", "ANEES",
             fmt::format("{:.3f}", mc.anees_mean), mc.band.lo, mc.band.hi,
             100.0 * mc.anees_fraction_in_band);
  if (mc.anees_infinite_steps > 0) {
    fmt::print("  {:<28}{:>14}   (the ANEES above leaves them out)\n", "steps with infinite NEES",
               mc.anees_infinite_steps);
  }
  fmt::print("  {:<28}{:>14}\n", "landmarks mapped (mean)",
             fmt::format("{:.1f}", mc.landmarks_mapped_mean));
  if (!config.ekf.known_association()) {
    fmt::print("  {:<28}{:>14}\n", "association precision", fmt::format("{:.4f}", a.Precision()));
    fmt::print("  {:<28}{:>14}\n", "association recall", fmt::format("{:.4f}", a.Recall()));
  }
  fmt::print("  {:<28}{:>14}\n", "step time mean [ms]",
             fmt::format("{:.4f}", 1e3 * mc.step_time_mean_s));
  fmt::print("  {:<28}{:>14}\n", "step time max [ms]",
             fmt::format("{:.4f}", 1e3 * mc.step_time_max_s));
}

void WriteFigures(const std::filesystem::path& dir, const ScenarioParams& scenario,
                  const MonteCarloResult& mc) {
  PathFigureData path;
  path.title = fmt::format("{}: run 0", scenario.name);
  path.truth = mc.first_run.truth;
  path.estimate = mc.first_run.estimate;
  path.true_landmarks = mc.world;
  path.map = mc.first_run.map;
  WritePathFigure(dir / "map.png", path);

  ConsistencyFigureData consistency;
  consistency.title = fmt::format("{}: {} Monte Carlo runs", scenario.name, mc.run_count);
  consistency.t_s = mc.t_s;
  consistency.anees = mc.anees;
  consistency.band_lo = mc.band.lo;
  consistency.band_hi = mc.band.hi;
  consistency.position_rmse_m = mc.position_rmse_m;
  consistency.heading_rmse_rad = mc.heading_rmse_rad;
  WriteConsistencyFigure(dir / "consistency.png", consistency);
}

// The filter --filter names: the scenario's EKF, or FastSLAM on the same vehicle and sensor with
// the scenario's association (known, or each particle's maximum likelihood) and new-landmark gate.
LandmarkFilterFactory FactoryOf(const McOptions& options, const ScenarioConfig& config) {
  if (options.filter == "ekf") return EkfSlamFactory(config);
  FastSlamParams fastslam;
  fastslam.proposal =
      options.filter == "fastslam1" ? FastSlamProposal::kMotion : FastSlamProposal::kObservation;
  fastslam.particles = options.particles;
  fastslam.known_association = config.ekf.known_association();
  fastslam.new_landmark_chi2 = config.ekf.association.new_landmark_chi2;
  fastslam.association_margin_m = config.ekf.association_margin_m;
  return FastSlamFactory(fastslam, config.scenario.vehicle, config.scenario.sensor);
}

int RunMonteCarloCommand(const McOptions& options) {
  ScenarioConfig config = LoadScenario(options.config);
  if (options.known_association) config.ekf.association_method = AssociationMethod::kKnown;
  if (options.unknown_association) {
    config.ekf.association_method = AssociationMethod::kNearestNeighbour;
  }
  OutputDir output(options.out);
  MonteCarloParams params;
  params.runs = options.runs;
  params.seed = options.seed;
  params.threads = options.threads > 0 ? options.threads : UsableCpuCount();
  params.known_association = config.ekf.known_association();
  auto progress = std::make_shared<Progress>("runs", options.runs);
  params.progress = [progress](int done, int total) {
    (void)total;
    progress->Update(done);
  };
  const std::filesystem::path& dir = output.staging();
  // Each run is written as it finishes and dropped, summary included, so memory stays flat
  // however many runs are asked for.
  params.keep_runs = false;
  params.keep_summaries = false;
  MonteCarloWriter writer(dir);
  params.on_run = [&writer](int k, const RunResult& run, const RunSummary& summary) {
    writer.Add(k, run, summary);
  };
  const MonteCarloResult mc = RunMonteCarlo(config.scenario, FactoryOf(options, config), params);
  // Figures first: metrics.json is written last, so its presence means the run completed.
  if (!options.no_figures) WriteFigures(dir, config.scenario, mc);
  nlohmann::json metrics = MonteCarloMetrics(config, params, mc);
  metrics["filter"] = options.filter;
  if (options.filter != "ekf") metrics["particles"] = options.particles;
  writer.Finish(metrics, mc);
  output.Commit();
  PrintSummary(config, mc);
  fmt::print("wrote {}\n", options.out);
  return 0;
}

void AddCommonOptions(CLI::App& cmd, McOptions& o) {
  cmd.add_option("--runs", o.runs, "Monte Carlo runs")->check(CLI::Range(1, 100000));
  cmd.add_option("--seed", o.seed, "master seed: run k uses stream k of it")
      ->check(SeedNumber());
  cmd.add_option("--threads", o.threads, "worker threads (0: all the CPUs this process may use)")
      ->check(CLI::Range(0, 1024));
  cmd.add_flag("--no-figures", o.no_figures, "skip the PNG figures");
  cmd.add_option("--filter", o.filter,
                 "ekf (the scenario's EKF-SLAM), fastslam1 or fastslam2 (Montemerlo et al. 2002, "
                 "2003: per-particle landmark EKFs in copy-on-write trees)")
      ->check(CLI::IsMember({"ekf", "fastslam1", "fastslam2"}))
      ->capture_default_str();
  cmd.add_option("--particles", o.particles, "FastSLAM's particle count")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd.add_flag("--known-association", o.known_association, "use the simulator's landmark ids");
  cmd.add_flag("--unknown-association", o.unknown_association,
               "nearest-neighbour association (overrides the config)");
}

}  // namespace

void RegisterMonteCarlo(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<McOptions>();
  CLI::App* cmd = app.add_subcommand("mc", "Monte Carlo EKF-SLAM runs on a simulated scenario");
  cmd->add_option("--config", options->config, "scenario YAML file (see docs/scenario.md)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options->out, "output directory")->required();
  AddCommonOptions(*cmd, *options);
  cmd->callback([options, &exit_code] { exit_code = RunMonteCarloCommand(*options); });
}

void RegisterDemo(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<McOptions>();
  options->config = std::string(SLAMKIT_SOURCE_DIR) + "/configs/default.yaml";
  options->out = "out/demo";
  options->runs = 20;
  CLI::App* cmd = app.add_subcommand(
      "demo", "the default demo: a car-like robot mapping a landmark world (SPEC S2)");
  cmd->add_option("--config", options->config, "scenario YAML file")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options->out, "output directory")->capture_default_str();
  AddCommonOptions(*cmd, *options);
  cmd->callback([options, &exit_code] { exit_code = RunMonteCarloCommand(*options); });
}

}  // namespace slamkit::app
