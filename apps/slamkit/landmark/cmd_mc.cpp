// `slamkit mc` and `slamkit demo`: Monte Carlo landmark SLAM (EKF-SLAM, FastSLAM 1.0 / 2.0) on a
// simulated scenario, on its route or with SWSLAM's self-detected waypoints.
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "common/options.hpp"
#include "landmark/mc_figures.hpp"
#include "common/output_dir.hpp"
#include "common/progress.hpp"
#include "slamkit/core/angle.hpp"
#include "slamkit/core/cpu.hpp"
#include "slamkit/report/figures.hpp"
#include "slamkit/runners/landmark/active_monte_carlo.hpp"
#include "slamkit/runners/landmark/active_outputs.hpp"
#include "slamkit/runners/landmark/filter_choice.hpp"
#include "slamkit/runners/landmark/outputs.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit::app {
namespace {

struct McOptions {
  std::string config;
  int runs = 50;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string filter = "ekf";  // ekf | fastslam1 | fastslam2
  int particles = FastSlamParams{}.particles;
  std::string planner;  // route | swslam; empty: the config's planner section
  std::string out;
  bool no_figures = false;
  bool unknown_association = false;
  bool known_association = false;
  std::string shard;  // K/N; empty: every run
};

void PrintSummary(const ScenarioConfig& config, const ActiveMonteCarloResult& result) {
  const MonteCarloResult& mc = result.mc;
  const ScenarioParams& scenario = config.scenario;
  const AssociationScore& a = mc.association;
  fmt::print("scenario {}: {} runs x {} steps, {} landmarks, {} association, planner {}\n",
             scenario.name, mc.run_count, mc.t_s.size(), mc.world.landmarks.size(),
             AssociationName(config.ekf.association_method), PlannerName(result.planner));
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
  fmt::print("{}", SectionMeansText(result.sections));
}

int RunMonteCarloCommand(const McOptions& options) {
  ScenarioConfig config = LoadScenario(options.config);
  if (options.known_association) config.ekf.association_method = AssociationMethod::kKnown;
  if (options.unknown_association) {
    config.ekf.association_method = AssociationMethod::kNearestNeighbour;
  }
  const FilterKind filter = ParseFilterKind(options.filter);
  const PlannerKind planner =
      options.planner.empty() ? config.planner.kind : ParsePlannerKind(options.planner);
  const LandmarkFilterFactory factory = FactoryForFilter(filter, options.particles, config);
  const Shard shard = options.shard.empty() ? Shard{} : ParseShard(options.shard);
  if (shard.count > options.runs) {
    throw CLI::ValidationError("--shard", fmt::format("{} parts of {} runs: N must be at most "
                                                      "--runs", shard.count, options.runs));
  }
  OutputDir output(options.out);
  ActiveMonteCarloParams params;
  params.mc.runs = options.runs;
  params.mc.seed = options.seed;
  params.mc.threads = options.threads > 0 ? options.threads : UsableCpuCount();
  params.mc.shard = shard;
  auto progress = std::make_shared<Progress>(
      "runs", RangeOfShard(options.runs, params.mc.shard).size());
  params.mc.progress = [progress](int done, int total) {
    (void)total;
    progress->Update(done);
  };
  const std::filesystem::path& dir = output.staging();
  // Each run is written as it finishes and dropped, summary and trace included, so memory stays
  // flat however many runs are asked for.
  params.mc.keep_runs = false;
  params.mc.keep_summaries = false;
  params.keep_traces = false;
  MonteCarloWriter writer(dir);
  params.on_run = [&writer](int k, const RunResult& run, const RunSummary& summary,
                            const ActiveRunTrace& trace) {
    writer.Add(k, run, summary, ActiveRunTraceJson(trace));
  };
  const ActiveMonteCarloResult result = RunActiveMonteCarlo(config, factory, planner, params);
  // Figures first: metrics.json is written last, so its presence means the run completed.
  if (!options.no_figures) {
    WriteMonteCarloFigures(dir, config.scenario.name, result,
                           RangeOfShard(options.runs, shard).begin);
  }
  writer.Finish(ActiveMonteCarloMetrics(config, params.mc, result, filter, options.particles),
                result.mc);
  output.Commit();
  PrintSummary(config, result);
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
  cmd.add_option("--shard", o.shard,
                 "K/N: run only the K-th of N contiguous parts of the runs (slamkit merge joins "
                 "the N output folders into the unsharded run's)")
      ->check(ShardText());
  cmd.add_option("--filter", o.filter,
                 "ekf (the scenario's EKF-SLAM), fastslam1 or fastslam2 (Montemerlo et al. 2002, "
                 "2003: per-particle landmark EKFs in copy-on-write trees)")
      ->check(CLI::IsMember({"ekf", "fastslam1", "fastslam2"}))
      ->capture_default_str();
  cmd.add_option("--particles", o.particles, "FastSLAM's particle count")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd.add_option("--planner", o.planner,
                 "route (drive the route) or swslam (self-detected waypoints, SPEC S2); default: "
                 "the config's planner section")
      ->check(CLI::IsMember({"route", "swslam"}));
  cmd.add_flag("--known-association", o.known_association, "use the simulator's landmark ids");
  cmd.add_flag("--unknown-association", o.unknown_association,
               "nearest-neighbour association (overrides the config)");
}

}  // namespace

void RegisterMonteCarlo(CLI::App& app, int& exit_code) {
  auto options = std::make_shared<McOptions>();
  CLI::App* cmd =
      app.add_subcommand("mc", "Monte Carlo landmark SLAM runs on a simulated scenario");
  AddExamples(cmd, {
               "--config configs/default.yaml --runs 20 --shard 1/2 --out out/default_1   # "
               "without --shard: all 20 runs",
               "--config configs/default.yaml --runs 20 --shard 2/2 --out out/default_2   # "
               "slamkit merge joins the two"});
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
  AddExamples(cmd, {
               "--runs 5 --out out/demo5"});
  cmd->add_option("--config", options->config, "scenario YAML file")
      ->capture_default_str()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", options->out, "output directory")->capture_default_str();
  AddCommonOptions(*cmd, *options);
  cmd->callback([options, &exit_code] { exit_code = RunMonteCarloCommand(*options); });
}

}  // namespace slamkit::app
