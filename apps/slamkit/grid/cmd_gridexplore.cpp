// `slamkit gridexplore`: SPEC S4's simulated exploration, the grid RBPF driving a frontier
// explorer, with P-SLAM's structure prediction on or off.
#include <cmath>
#include <cstdint>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "grid/grid_outputs.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "grid/plan_input.hpp"
#include "common/progress.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/grid_writers.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/runners/grid/grid_explore.hpp"
#include "slamkit/sim/maze_route.hpp"

namespace slamkit::app {
namespace {

struct GridExploreOptions {
  std::string plan = "maze";
  std::string start;  // "x,y,theta"; the maze route's start for the maze
  std::string predict = "off";
  std::string recovery = "on";
  std::string out;
  std::uint64_t sim_seed = 1;
  GridExploreParams explore;
  GridSlamConfig slam;
};

Pose2 StartPose(const GridExploreOptions& o) {
  if (o.start.empty()) {
    if (o.plan != "maze") throw InputError("--plan " + o.plan + ": give --start x,y,theta");
    return RouteStartPose(MazeRoute({}, 1));
  }
  std::vector<double> v;
  std::stringstream in(o.start);
  for (std::string item; std::getline(in, item, ',');) {
    try {
      std::size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size()) v.clear();
    } catch (const std::exception&) {
      v.clear();
    }
    if (v.empty()) break;
  }
  if (v.size() != 3 || !std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
    throw InputError("--start '" + o.start + "': expected x,y,theta (metres, radians)");
  }
  return {v[0], v[1], v[2]};
}

void WriteOutputs(const std::filesystem::path& dir, const GridExploreOptions& o,
                  const GridExploreResult& r) {
  WriteGridOutputs(dir, r.slam, r.odometry, "explored map");
  WriteTumTrajectory(dir / "truth.tum", r.truth);
  WriteOccupancyGridPgm(dir / "truth.pgm", r.truth_map);  // the plan's true map, for mapdiff
  WriteJson(dir / "metrics.json",
            GridExploreMetrics(r, o.explore, o.sim_seed, o.slam, PeakRssMib()));
  if (!o.explore.predict) return;
  WritePredictionOutputs(dir, r.slam, r.hypotheses, r.predicted);
}

void PrintSummary(const GridExploreOptions& o, const GridExploreResult& r) {
  PrintGridRun(o.plan, r.slam, o.slam.rbpf.particles);
  PrintComparison("truth", r.vs_truth);
  fmt::print("  {:<28}{:>12}\n", "exploration",
             fmt::format("{} in {:.1f} s, {:.1f} m, {} targets, {:.2f} m from walls at least",
                         r.finished ? "finished" : "stopped", r.exploration_time_s,
                         r.path_length_m, r.targets, r.closest_wall_m));
  fmt::print("  {:<28}{:>12}\n", "explored map vs truth",
             fmt::format("psi {:.3f}, accuracy {:.3f}", r.explored_vs_truth.dice_occupied,
                         r.explored_vs_truth.cell_accuracy));
  if (!o.explore.predict) return;
  fmt::print("  {:<28}{:>12}\n", "with predictions vs truth",
             fmt::format("psi {:.3f}, accuracy {:.3f}; {} hypotheses, {:.1f} m2 predicted",
                         r.combined_vs_truth.dice_occupied, r.combined_vs_truth.cell_accuracy,
                         r.hypotheses.size(), r.predicted_area_m2));
}

int RunGridExploreCommand(GridExploreOptions o) {
  const FloorPlan plan = ReadPlan(o.plan);
  const Pose2 start = StartPose(o);
  OutputDir output(o.out);
  o.explore.predict = o.predict == "on";
  o.explore.prediction.recovery = o.recovery == "on";
  Progress progress("simulated s", static_cast<int>(o.explore.max_time_s));
  const GridExploreResult result = RunGridExploration(
      plan, start, o.sim_seed, o.slam, o.explore,
      [&progress](double t_s, double) { progress.Update(static_cast<int>(t_s)); });
  WriteOutputs(output.staging(), o, result);
  output.Commit();
  PrintSummary(o, result);
  fmt::print("wrote {}\n", o.out);
  return 0;
}

void AddExploreOptions(CLI::App* cmd, GridExploreOptions& o) {
  cmd->add_option("--plan", o.plan,
                  "'maze' (SPEC S4's 25 m maze), a map_server map.yaml, or a walls file "
                  "(`x1 y1 x2 y2` and `poly ...` lines in metres)")
      ->capture_default_str();
  cmd->add_option("--start", o.start, "start pose x,y,theta [m, m, rad] (required with a file)");
  cmd->add_option("--predict", o.predict, "P-SLAM's structure prediction, skipping what it "
                  "predicted")->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  cmd->add_option("--recovery", o.recovery, "drop predictions the scans do not support (Eq. 23)")
      ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  cmd->add_option("--similarity-threshold", o.explore.predictor.similarity_threshold,
                  "least Psi (Eq. 5) for a hypothesis")
      ->check(CLI::Range(0.0, 1.0))->capture_default_str();
  cmd->add_option("--region-diameter", o.explore.predictor.region_diameter_m,
                  "d: the prediction compares and fills the disc of this diameter around the "
                  "target [m]")->check(CLI::Range(1.0, 100.0))->capture_default_str();
  cmd->add_option("--prediction-delay-scans", o.explore.prediction.deterministic_delay_scans,
                  "take each prediction exactly N scans after its request (0: when the thread "
                  "has it, not reproducible)")->check(CLI::Range(0, 100000))->capture_default_str();
  cmd->add_option("--sim-seed", o.sim_seed, "random seed of the simulated robot")
      ->check(SeedNumber())->capture_default_str();
  cmd->add_option("--max-time", o.explore.max_time_s, "stop after this much simulated time [s]")
      ->check(CLI::Range(1.0, 1e6))->capture_default_str();
  cmd->add_option("--odom-sigma-v", o.explore.sigma_v_mps, "odometry noise on the speed [m/s]")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--odom-sigma-omega", o.explore.sigma_omega_radps,
                  "odometry noise on the turn rate [rad/s]")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--laser-range", o.explore.laser.range_limit_m, "laser range [m]")
      ->check(CLI::Range(0.5, 80.0))->capture_default_str();
}

}  // namespace

void RegisterGridExplore(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<GridExploreOptions>();
  o->slam.rbpf.grid.resolution_m = 0.1;  // SPEC S4's grid
  CLI::App* cmd = app.add_subcommand(
      "gridexplore",
      "SPEC S4's simulated exploration: the grid RBPF drives a frontier explorer, with or "
      "without P-SLAM's structure prediction");
  AddExamples(cmd, {
               "--plan maze --predict on --seed 1 --out out/maze_explore"});
  cmd->add_option("--out", o->out, "output directory")->required();
  AddExploreOptions(cmd, *o);
  AddGridFilterOptions(cmd, o->slam);
  cmd->callback([o, &exit_code] { exit_code = RunGridExploreCommand(*o); });
}

}  // namespace slamkit::app
