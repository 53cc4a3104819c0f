// `slamkit coop`: SPEC S3's cooperative EKF-SLAM on a simulated fleet (Monte Carlo) or on the
// robots of an MRCLAM data set, every chosen estimator on the same inputs.
#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "cooperative/coop_figures.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "common/progress.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/mrclam_reader.hpp"
#include "slamkit/runners/cooperative/coop_config.hpp"
#include "slamkit/runners/cooperative/coop_study.hpp"

namespace slamkit::app {
namespace {

struct CoopOptions {
  std::string config;
  std::string mrclam;
  std::string robots;
  std::string mode = "all";
  std::string association;
  double start_s = 0.0;
  double duration_s = 0.0;
  int features = 0;
  std::string out;
  bool no_figures = false;
  std::string command;
};

std::vector<CoopMode> ModesOf(const std::string& name, bool data_set) {
  if (name == "all") {
    std::vector<CoopMode> modes = {CoopMode::kMono, CoopMode::kExtended, CoopMode::kExact,
                                   CoopMode::kCentral};
    // On a data set, what Mono starts from and what Mono's data allow at best come too.
    if (data_set) {
      modes.insert(modes.begin(), CoopMode::kDeadReckoning);
      modes.push_back(CoopMode::kMonoSmoothed);
    }
    return modes;
  }
  return {*CoopModeFromName(name)};
}

std::vector<int> RobotsOf(const std::string& text) {
  std::vector<int> robots;
  for (const std::uint64_t r : ParseSeeds(text)) robots.push_back(static_cast<int>(r));
  return robots;
}

void PrintSummary(const CoopStudyResult& r) {
  fmt::print("{:<15}{:>8}{:>14}{:>13}{:>14}{:>10}{:>10}{:>11}{:>8}{:>12}{:>12}\n", "mode",
             "vehicle", "position [m]", "aligned [m]", "heading [rad]", "ANEES", "map [m]",
             "landmarks", "assoc", "IR mean %", "update [ms]");
  for (const CoopModeSummary& m : r.modes) {
    for (std::size_t v = 0; v < m.vehicles.size(); ++v) {
      const CoopVehicleSummary& s = m.vehicles[v];
      const std::string aligned = s.position_aligned_rmse_m >= 0.0
                                      ? fmt::format("{:.4f}", s.position_aligned_rmse_m)
                                      : "-";
      fmt::print(
          "{:<15}{:>8}{:>14.4f}{:>13}{:>14.4f}{:>10.3f}{:>10}{:>11.1f}{:>8}{:>12.1f}{:>12.3f}\n",
          CoopModeName(m.mode), v, s.position_rmse_m, aligned, s.heading_rmse_rad, s.anees,
          s.map_rmse_m >= 0.0 ? fmt::format("{:.3f}", s.map_rmse_m) : "-", s.landmarks,
          s.association_agreement >= 0.0 ? fmt::format("{:.3f}", s.association_agreement) : "-",
          s.improvement_ratio_mean_pct, 1e3 * m.update_time_mean_s);
    }
  }
  fmt::print("ANEES band for {} runs: [{:.3f}, {:.3f}]\n", r.runs,
             r.modes.empty() ? 0.0 : r.modes[0].band.lo, r.modes.empty() ? 0.0 : r.modes[0].band.hi);
}

int RunCoopCommand(const CoopOptions& o, CoopConfig config) {
  const bool data_set = !o.mrclam.empty();
  if (o.features > 0) {
    config.scenario.world.kind = WorldSpec::Kind::kUniform;
    config.scenario.world.uniform.count = o.features;
  }
  if (!o.association.empty()) {
    config.filter.known_association = o.association == "known";
    if (!config.filter.known_association) {
      const std::vector<std::string> names = {"nn", "known", "jcbb", "ml", "gnn"};
      const auto it = std::find(names.begin(), names.end(), o.association);
      config.filter.filter.ekf.association_method =
          static_cast<AssociationMethod>(it - names.begin());
    }
  }
  const std::vector<CoopMode> modes = ModesOf(o.mode, data_set);
  CoopStudyResult result;
  OutputDir output(o.out);
  if (data_set) {
    MrclamSelection selection;
    if (!o.robots.empty()) selection.robots = RobotsOf(o.robots);
    selection.start_s = o.start_s;
    if (o.duration_s > 0.0) selection.duration_s = o.duration_s;
    const auto [log, truth] = MrclamFleet(ReadMrclam(o.mrclam), selection);
    result = RunCoopLog(log, truth, {}, config.filter, modes, config.seed);
  } else {
    Progress bar("coop runs", config.runs);
    result = RunCoopStudy(config, modes, [&bar](int done, int) { bar.Update(done); });
  }
  const std::filesystem::path& dir = output.staging();
  if (!o.no_figures) WriteCoopFigures(dir, result);
  WriteCoopOutputs(dir, result, CoopConfigJson(config), o.command);
  output.Commit();
  PrintSummary(result);
  fmt::print("wrote {}\n", o.out);
  return 0;
}

}  // namespace

void RegisterCoop(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<CoopOptions>();
  auto config = std::make_shared<CoopConfig>();
  CLI::App* cmd = app.add_subcommand(
      "coop",
      "cooperative EKF-SLAM (SPEC S3): Mono, EO-CSLAM, its exact form and the centralised "
      "filter on a simulated fleet or an MRCLAM data set");
  AddExamples(cmd, {
               "--config configs/marine_eo.yaml --runs 50 --out out/coop",
               "--mrclam ../shared/datasets/mrclam/MRCLAM_Dataset6 --config configs/mrclam.yaml --out out/mrclam"});
  cmd->add_option("--config", o->config, "cooperative config (configs/marine_eo.yaml, "
                                         "configs/mrclam.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--mrclam", o->mrclam, "an MRCLAM data set folder instead of the simulation")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--robots", o->robots, "MRCLAM robots to run, e.g. 1,2,3 or 1-5 (default all)");
  cmd->add_option("--start", o->start_s, "MRCLAM: seconds after the first odometry")
      ->check(NonNegativeNumber());
  cmd->add_option("--duration", o->duration_s, "MRCLAM: seconds to run (0: to the end)")
      ->check(NonNegativeNumber());
  cmd->add_option("--mode", o->mode,
                  "mono, eo, eo-exact, central, dead-reckoning, mono-smoothed or all")
      ->check(CLI::IsMember(
          {"all", "mono", "eo", "eo-exact", "central", "dead-reckoning", "mono-smoothed"}))
      ->capture_default_str();
  cmd->add_option("--association", o->association,
                  "known (ids of the source) or nn, jcbb, ml, gnn (default: the config's)")
      ->check(CLI::IsMember({"known", "nn", "jcbb", "ml", "gnn"}));
  cmd->add_option("--features", o->features, "simulation: this many uniform landmarks instead")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--out", o->out, "output directory")->required();
  cmd->add_flag("--no-figures", o->no_figures, "skip the PNG figures");
  const std::vector<CLI::Option*> table = AddParamOptions(cmd, CoopParamTable(*config));
  cmd->callback([o, config, table, &exit_code] {
    // The file's values, then the flags given on the command line over them.
    CoopConfig loaded = LoadCoopConfig(o->config);
    CoopConfig from_flags = *config;
    if (table[0]->count() > 0) loaded.runs = from_flags.runs;
    if (table[1]->count() > 0) loaded.seed = from_flags.seed;
    o->command = fmt::format("slamkit coop --config {}{} --mode {} --runs {} --seed {} --out {}",
                             o->config, o->mrclam.empty() ? "" : " --mrclam " + o->mrclam,
                             o->mode, loaded.runs, loaded.seed, o->out);
    exit_code = RunCoopCommand(*o, loaded);
  });
}

}  // namespace slamkit::app
