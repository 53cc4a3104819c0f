#pragma once

#include <vector>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/filters/exploration_slam.hpp"
#include "slamkit/planning/frontier_explorer.hpp"
#include "slamkit/sim/floor_plan.hpp"
#include "slamkit/sim/laser_sim.hpp"

namespace slamkit {

// How a SLAM step's time is taken: measured (noisy, machine-dependent) or modelled from its work,
// so that the same seed gives the same path.
enum class SlamTiming { kWallClock, kModelledCost };

struct ExplorationParams {
  double control_period_s = 0.1;  // the seed's
  double max_time_s = 900.0;      // simulated time
  // Odometry noise: each period the odometry integrates the command plus N(0, σ²) on v and ω.
  double sigma_v_mps = 0.02;
  double sigma_omega_radps = 0.02;
  LaserSimParams laser = SpecS1Laser();
  FrontierExplorerParams explorer;
  SlamTiming timing = SlamTiming::kModelledCost;

};

struct ExplorationRun {
  // One entry per SLAM step, at the scan's time.
  Trajectory truth;
  Trajectory estimate;
  Trajectory odometry;
  std::vector<double> slam_time_s;  // per step, as ExplorationParams::timing says
  // Per step, what the explorer was given (the estimate carried to the command's start, at that
  // time; the scan is the step's) and the command it gave: its inputs, to check what it reads.
  Trajectory planner_pose;
  std::vector<Control> commands;
  double open_loop_time_s = 0.0;    // Σ ⌈t / period⌉ · period over the steps
  double elapsed_s = 0.0;           // simulated time at the end
  ExplorerMode final_mode = ExplorerMode::kTurning;
};

// SPEC S1, active loop: the robot scans, the SLAM steps (taking t seconds), the robot holds its
// previous command for ⌈t / period⌉ · period (the open-loop time), then the explorer gives the next
// command from the estimate carried forward by the odometry of the hold, applied for one period.
// Until the explorer is done or max_time_s. All noise is drawn from `rng`.
ExplorationRun RunExploration(const FloorPlan& plan, const Pose2& start, ExplorationSlam& slam,
                              const ExplorationParams& params, Rng& rng);

}  // namespace slamkit
