#pragma once

#include <numbers>
#include <vector>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/sim/controller.hpp"
#include "slamkit/sim/floor_plan.hpp"

namespace slamkit {

// A planar laser range finder in a FloorPlan (SPEC S4). Beam angles follow the CARMEN logs: an
// even count splits the field of view into equal sectors and points at their starts (180 beams:
// −90°, −89°, …, 89°); an odd count spans it end to end (181 beams: −90°, …, 90°); a single beam
// looks straight ahead.
struct LaserSimParams {
  int beams = 180;
  double fov_rad = std::numbers::pi;
  double max_range_m = 80.0;     // the value written for a beam with no return (a SICK LMS's)
  double range_limit_m = 30.0;   // walls at or beyond this (or max_range_m) give no return
  double sigma_range_m = 0.01;   // Gaussian range noise, on returns only
  Pose2 laser_offset;            // the laser in the robot frame
};

// SPEC S1's laser (a SICK as the seed used it): 181 beams over 180°, 1° apart, 10 m used, beams
// without a return written at 10 m, σ 1 cm.
LaserSimParams SpecS1Laser();

// One scan from the robot at `robot_pose` (the laser at robot_pose ⊕ laser_offset). Fills ranges,
// angles, max_range_m and laser_offset; t_s, odometry and logged_pose are left for the caller.
LaserScan SimulateScan(const FloorPlan& plan, const Pose2& robot_pose,
                       const LaserSimParams& params, Rng& rng);

// A robot driving a route through a FloorPlan and logging a scan every step, like a CARMEN log.
struct GridSimParams {
  // Odometry noise: each step the odometry integrates the commanded (v, ω) plus independent
  // N(0, σ²) noise on each, as UnicycleParams describes; the true robot moves noise-free.
  double sigma_v_mps = 0.05;
  double sigma_omega_radps = 0.02;
  double dt_s = 0.1;
  double speed_mps = 0.5;          // replaces controller.speed_mps
  RouteParams route;
  ControllerParams controller;     // driven as MotionKind::kUnicycle
  int max_steps = 100000;          // stop earlier when the route is done
  LaserSimParams laser;
};

// A simulated laser run as two streams: what the filter receives (the scans, as a raw CARMEN log
// gives them) and, beside it, the truth.
struct GridSimRun {
  // Scan k is taken at t_s = k·dt_s (scan 0 at the start pose): `odometry` is the noisy odometry
  // (in a frame that coincides with the world at the start) and `logged_pose` the same odometry,
  // as in a raw (uncorrected) log. Neither is the true pose.
  std::vector<LaserScan> scans;
  Trajectory truth;  // the true pose at each scan's time, parallel to `scans`
};

// Drives the route with WaypointController from `start`, drawing all noise from `rng` (so a seed
// fixes the run). The robot does not collide: a route must keep it off the walls.
GridSimRun SimulateGridRun(const FloorPlan& plan, const GridSimParams& params, const Pose2& start,
                           Rng& rng);

}  // namespace slamkit
