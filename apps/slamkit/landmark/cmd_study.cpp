// `slamkit study`: seed 001's experiment (SPEC S2), EKF-SLAM and FastSLAM on the route against
// SWSLAM on the same worlds and seeds, with the seed's Tables 1-5 beside ours.
#include <array>
#include <filesystem>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "common/progress.hpp"
#include "slamkit/core/cpu.hpp"
#include "slamkit/runners/landmark/active_outputs.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"
#include "slamkit/runners/landmark/study.hpp"
#include "slamkit/runners/landmark/study_outputs.hpp"
#include "landmark/study_figures.hpp"

namespace slamkit::app {
namespace {

struct StudyOptions {
  std::string config;
  std::string out;
  int runs = StudyParams{}.runs;
  std::uint64_t seed = StudyParams{}.seed;
  int threads = 0;
  int particles = StudyParams{}.particles;
  std::string filter = std::string(FilterName(StudyParams{}.fastslam));
  bool no_figures = false;
};

// One line per method (position and heading: the mean over runs of each run's RMS), then its
// sections; tables.md sets them beside the paper's.
void PrintSummary(const StudyResult& result) {
  fmt::print("{:<14}{:>11}{:>9}{:>12}{:>14}{:>15}{:>10}\n", "method", "ANEES", "in band",
             "median run", "position [m]", "heading [rad]", "time [s]");
  for (const StudyMethodResult& m : result.methods) {
    fmt::print("{:<14}{:>11.4g}{:>8.0f}%{:>12.4g}{:>14.4f}{:>15.4f}{:>10.1f}\n", m.title,
               m.mc.anees_mean, 100.0 * m.mc.anees_fraction_in_band, m.anees_run_median,
               m.position_rms_m.mean, m.heading_rms_rad.mean, m.wall_time_s);
    fmt::print("{}", SectionMeansText(m.sections));
  }
}

int RunStudyCommand(const StudyOptions& o) {
  const ScenarioConfig config = LoadScenario(o.config);
  OutputDir output(o.out);
  StudyParams params;
  params.runs = o.runs;
  params.seed = o.seed;
  params.threads = o.threads > 0 ? o.threads : UsableCpuCount();
  params.particles = o.particles;
  params.fastslam = ParseFilterKind(o.filter);
  // One progress line per method: they run one after the other, each starting at 0 finished.
  auto bars = std::make_shared<std::array<std::unique_ptr<Progress>, 3>>();
  params.progress = [bars, &params](int method, int done, int total) {
    auto& bar = (*bars)[static_cast<std::size_t>(method)];
    if (!bar) bar = std::make_unique<Progress>(StudyMethodTitle(method, params) + " runs", total);
    bar->Update(done);
  };
  const StudyResult result = RunStudy(config, params);
  const std::filesystem::path& dir = output.staging();
  if (!o.no_figures) WriteStudyFigures(dir, config.scenario.name, result);
  WriteStudyOutputs(dir, config, result);  // metrics.json last
  output.Commit();
  PrintSummary(result);
  fmt::print("wrote {}\n", o.out);
  return 0;
}

}  // namespace

void RegisterStudy(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<StudyOptions>();
  CLI::App* cmd = app.add_subcommand(
      "study",
      "seed 001's experiment (SPEC S2): EKF-SLAM and FastSLAM on the route against "
      "SWSLAM, Tables 1-5 beside the paper's");
  AddExamples(cmd, {
               "--config configs/swslam.yaml --runs 10 --out out/study"});
  cmd->add_option("--config", o->config,
                  "scenario YAML file with a planner section "
                  "(configs/swslam.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "output directory")->required();
  cmd->add_option("--runs", o->runs, "Monte Carlo runs per method")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "master seed: run k of every method uses stream k of it")
      ->check(SeedNumber())
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "worker threads (0: all the CPUs this process may use)")
      ->check(CLI::Range(0, 1024));
  cmd->add_option("--filter", o->filter, "the FastSLAM run on the route: fastslam1 or fastslam2")
      ->check(CLI::IsMember({"fastslam1", "fastslam2"}))
      ->capture_default_str();
  cmd->add_option("--particles", o->particles, "FastSLAM's particle count")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_flag("--no-figures", o->no_figures, "skip the PNG figures");
  cmd->callback([o, &exit_code] { exit_code = RunStudyCommand(*o); });
}

}  // namespace slamkit::app
