#include "slamkit/runners/features/exploration.hpp"

#include <chrono>
#include <cmath>

#include "slamkit/models/unicycle.hpp"

namespace slamkit {

namespace {

// The true robot (noise-free) and its odometry (the command plus noise), driven one control
// period at a time by the unicycle model.
struct Robot {
  Pose2 truth;
  Pose2 odometry;

  void Drive(const Control& u, const ExplorationParams& params, Rng& rng) {
    const UnicycleModel unicycle;
    const double dt = params.control_period_s;
    truth = unicycle.Move(truth, u, dt);
    Control noisy(2);
    noisy << u(0) + rng.Normal(0.0, params.sigma_v_mps),
        u(1) + rng.Normal(0.0, params.sigma_omega_radps);
    odometry = unicycle.Move(odometry, noisy, dt);
  }
};

double TimedStep(ExplorationSlam& slam, const Pose2& delta, const LaserScan& scan,
                 SlamTiming timing) {
  const auto start = std::chrono::steady_clock::now();
  slam.Step(delta, scan);
  if (timing == SlamTiming::kModelledCost) return slam.ModelledCostS();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

// SPEC S1, active loop, with the seed's open-loop time: the command in force while the SLAM
// computes is the previous one.
ExplorationRun RunExploration(const FloorPlan& plan, const Pose2& start, ExplorationSlam& slam,
                              const ExplorationParams& params, Rng& rng) {
  ExplorationRun run;
  FrontierExplorer explorer(params.explorer);
  Robot robot{start, start};  // the odometry frame is the world's at the start
  Pose2 odometry_at_last_step = start;
  Control u = Control::Zero(2);
  const double period = params.control_period_s;
  double t = 0.0;
  while (t < params.max_time_s && explorer.mode() != ExplorerMode::kDone) {
    LaserScan scan = SimulateScan(plan, robot.truth, params.laser, rng);
    scan.t_s = t;
    scan.odometry = robot.odometry;
    const double cost =
        TimedStep(slam, odometry_at_last_step.Between(robot.odometry), scan, params.timing);
    odometry_at_last_step = robot.odometry;
    run.truth.push_back({t, robot.truth});
    run.estimate.push_back({t, slam.Estimate()});
    run.odometry.push_back({t, robot.odometry});
    run.slam_time_s.push_back(cost);
    const int held = static_cast<int>(std::ceil(cost / period - 1e-9));
    run.open_loop_time_s += held * period;
    for (int k = 0; k < held; ++k) robot.Drive(u, params, rng);
    t += held * period;
    // The estimate at the scan, carried to now by the odometry of the hold.
    const Pose2 now = slam.Estimate().Compose(odometry_at_last_step.Between(robot.odometry));
    u = explorer.Step(now, scan, t);
    run.planner_pose.push_back({t, now});
    run.commands.push_back(u);
    robot.Drive(u, params, rng);
    t += period;
  }
  run.elapsed_s = t;
  run.final_mode = explorer.mode();
  return run;
}

}  // namespace slamkit
