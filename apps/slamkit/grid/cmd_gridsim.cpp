// `slamkit gridsim`: occupancy-grid RBPF SLAM on a simulated laser run through a floor plan
// (SPEC S4's square maze by default, a map_server map or a walls file), compared with the true
// path.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "grid/grid_outputs.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "grid/plan_input.hpp"
#include "common/progress.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/waypoints_reader.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/runners/grid/grid_sim.hpp"
#include "slamkit/sim/maze_route.hpp"

namespace slamkit::app {
namespace {

// The tightest turn the simulated robot makes, whatever its speed: MazeRoute's switch distance
// is laid out for it (a wider turn cuts the maze's corners into the walls).
constexpr double kTurnRadiusM = 0.5;

struct GridSimOptions {
  std::string plan = "maze";
  std::string waypoints;
  std::string out;
  std::uint64_t sim_seed = 1;
  int max_steps = 0;
  GridSimParams sim;
  GridSlamConfig slam;
};

// The floor plan and the route the options name; errors (files, a missing route) come here,
// before the long run.
std::pair<FloorPlan, RouteParams> PlanAndRoute(const GridSimOptions& o) {
  const bool maze = o.plan == "maze";
  if (!maze && o.waypoints.empty()) {
    throw InputError(fmt::format("--plan {}: a plan file needs its route: --waypoints FILE "
                                 "(one `x y` line per waypoint, in metres)", o.plan));
  }
  FloorPlan plan = ReadPlan(o.plan);
  // A given route turns at its waypoints as tightly as the maze route does.
  RouteParams route = MazeRoute({}, o.sim.route.loops);
  if (!o.waypoints.empty()) route.waypoints_m = ReadWaypoints(o.waypoints);
  return {std::move(plan), std::move(route)};
}

void PrintSummary(const GridSimOptions& o, const GridSimResult& r) {
  PrintGridRun(o.plan, r.slam, o.slam.rbpf.particles);
  PrintComparison("truth", r.vs_truth);
  fmt::print("  {:<28}{:>12}\n", "odometry ATE vs truth [m]",
             fmt::format("{:.4f} rms, {:.4f} max", r.odometry_vs_truth.ate.rmse_m,
                         r.odometry_vs_truth.ate.max_m));
}

int RunGridSimCommand(GridSimOptions o) {
  auto [plan, route] = PlanAndRoute(o);
  OutputDir output(o.out);
  o.sim.route = std::move(route);
  if (o.max_steps > 0) o.sim.max_steps = o.max_steps;
  o.sim.controller.max_turn_rate_radps =
      std::max(o.sim.controller.max_turn_rate_radps, o.sim.speed_mps / kTurnRadiusM);

  std::unique_ptr<Progress> progress;  // made once the simulation has told the scan count
  const GridSimResult result = RunGridSimulation(
      plan, o.sim, RouteStartPose(o.sim.route), o.sim_seed, o.slam,
      [&progress](int done, int total) {
        if (!progress) progress = std::make_unique<Progress>("scans", total);
        progress->Update(done);
      });

  if (o.max_steps == 0 && result.slam.scans > o.sim.max_steps) {
    PrintStderr("note: the run stopped at the step limit ({}) before the route's end\n",
               o.sim.max_steps);
  }

  const std::filesystem::path& dir = output.staging();
  WriteGridOutputs(dir, result.slam);
  WriteTumTrajectory(dir / "truth.tum", result.truth);
  WriteJson(dir / "metrics.json",
            GridSimMetrics(result, o.sim, o.sim_seed, o.slam, PeakRssMib()));
  output.Commit();
  PrintSummary(o, result);
  fmt::print("wrote {}\n", o.out);
  return 0;
}

void AddSimulationOptions(CLI::App* cmd, GridSimOptions& o) {
  cmd->add_option("--plan", o.plan,
                  "'maze' (SPEC S4's 25 m maze), a map_server map.yaml, or any other file: "
                  "walls `x1 y1 x2 y2` and polygons `poly x1 y1 x2 y2 x3 y3 ...` in metres")
      ->capture_default_str();
  cmd->add_option("--waypoints", o.waypoints,
                  "route: `x y` lines in metres (required with a plan file)")
      ->check(CLI::ExistingFile);
  cmd->add_option("--sim-seed", o.sim_seed, "random seed of the simulated run")
      ->check(SeedNumber())
      ->capture_default_str();
  cmd->add_option("--loops", o.sim.route.loops, "times around the route")->capture_default_str()
      ->check(CLI::Range(1, 100));
  // Above 1 m/s the 0.1 s steps are too coarse for 0.5 m turns in the maze's corridors.
  cmd->add_option("--speed", o.sim.speed_mps, "robot speed [m/s] (turns keep a 0.5 m radius)")
      ->capture_default_str()->check(CLI::Range(0.1, 1.0));
  cmd->add_option("--odom-sigma-v", o.sim.sigma_v_mps, "odometry noise on the speed [m/s]")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--odom-sigma-omega", o.sim.sigma_omega_radps,
                  "odometry noise on the turn rate [rad/s]")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--max-steps", o.max_steps,
                  fmt::format("stop after N steps of {} s (0: the whole route, at most {})",
                              o.sim.dt_s, o.sim.max_steps))
      ->check(NonNegativeNumber());
}

}  // namespace

void RegisterGridSim(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<GridSimOptions>();
  CLI::App* cmd = app.add_subcommand(
      "gridsim",
      "occupancy-grid RBPF SLAM on a simulated laser run (SPEC S4 maze, a map or a walls file)");
  AddExamples(cmd, {
               "--plan maze --out out/maze_sim",
               "--plan examples/plans/room_with_pillar.txt --waypoints examples/plans/room_with_pillar_route.txt --loops 2 --out out/room_sim"});
  cmd->add_option("--out", o->out, "output directory")->required();
  AddSimulationOptions(cmd, *o);
  AddGridFilterOptions(cmd, o->slam);
  cmd->callback([o, &exit_code] {
    exit_code = RunGridSimCommand(*o);
  });
}

}  // namespace slamkit::app
