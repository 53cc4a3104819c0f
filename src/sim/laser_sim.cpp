// The grid-world laser simulator of SPEC S4: scans cast against a FloorPlan, and logged runs of a
// unicycle robot driving a route with noisy odometry.

#include "slamkit/sim/laser_sim.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "slamkit/models/unicycle.hpp"

namespace slamkit {
namespace {

void CheckLaserParams(const LaserSimParams& params) {
  if (params.beams < 1) throw std::invalid_argument("SimulateScan: beams must be >= 1");
  if (!std::isfinite(params.fov_rad) || params.fov_rad < 0.0) {
    throw std::invalid_argument("SimulateScan: fov_rad must be finite and >= 0");
  }
  if (!(params.max_range_m > 0.0) || !(params.range_limit_m > 0.0)) {
    throw std::invalid_argument("SimulateScan: max_range_m and range_limit_m must be > 0");
  }
  if (!(params.sigma_range_m >= 0.0)) {
    throw std::invalid_argument("SimulateScan: sigma_range_m must be >= 0");
  }
}

void SetBeamAngles(const LaserSimParams& params, LaserScan* scan) {
  if (params.beams == 1) {
    scan->angle_min_rad = 0.0;
    scan->angle_increment_rad = 0.0;
    return;
  }
  scan->angle_min_rad = -0.5 * params.fov_rad;
  const int sectors = params.beams % 2 == 0 ? params.beams : params.beams - 1;
  scan->angle_increment_rad = params.fov_rad / sectors;
}

// The float written for "no return": max_range_m rounded up, so that LaserScan::IsReturn, which
// compares the float range with the double max_range_m, never takes it for a return.
float NoReturnRange(double max_range_m) {
  float range = static_cast<float>(max_range_m);
  if (range < max_range_m) range = std::nextafter(range, std::numeric_limits<float>::infinity());
  return range;
}

LaserScan ScanWith(const RayCaster& caster, const Pose2& robot_pose, const LaserSimParams& params,
                   Rng& rng) {
  LaserScan scan;
  SetBeamAngles(params, &scan);
  scan.max_range_m = params.max_range_m;
  scan.laser_offset = params.laser_offset;
  const Pose2 laser = robot_pose.Compose(params.laser_offset);
  // Anything at or past max_range_m would read as a no-return anyway.
  const double limit_m = std::min(params.range_limit_m, params.max_range_m);
  const float no_return = NoReturnRange(params.max_range_m);
  scan.ranges_m.reserve(params.beams);
  for (int i = 0; i < params.beams; ++i) {
    const double angle_rad = laser.theta() + scan.BeamAngle(i);
    const Eigen::Vector2d direction(std::cos(angle_rad), std::sin(angle_rad));
    double range_m = caster.Cast(laser.translation(), direction, limit_m);
    if (range_m >= limit_m) {
      scan.ranges_m.push_back(no_return);
      continue;
    }
    if (params.sigma_range_m > 0.0) range_m += rng.Normal(0.0, params.sigma_range_m);
    scan.ranges_m.push_back(static_cast<float>(std::max(0.0, range_m)));
  }
  return scan;
}

void CheckRunParams(const GridSimParams& params) {
  if (!(params.dt_s > 0.0)) throw std::invalid_argument("SimulateGridRun: dt_s must be > 0");
  if (!(params.sigma_v_mps >= 0.0) || !(params.sigma_omega_radps >= 0.0)) {
    throw std::invalid_argument("SimulateGridRun: odometry sigmas must be >= 0");
  }
  CheckLaserParams(params.laser);
}

}  // namespace

LaserSimParams SpecS1Laser() {
  LaserSimParams laser;
  laser.beams = 181;
  laser.max_range_m = 10.0;
  laser.range_limit_m = 10.0;
  laser.sigma_range_m = 0.01;
  return laser;
}

LaserScan SimulateScan(const FloorPlan& plan, const Pose2& robot_pose,
                       const LaserSimParams& params, Rng& rng) {
  CheckLaserParams(params);
  return ScanWith(RayCaster(plan), robot_pose, params, rng);
}

GridSimRun SimulateGridRun(const FloorPlan& plan, const GridSimParams& params, const Pose2& start,
                           Rng& rng) {
  CheckRunParams(params);
  ControllerParams controller_params = params.controller;
  controller_params.speed_mps = params.speed_mps;
  WaypointController controller(params.route, controller_params, MotionKind::kUnicycle);
  const UnicycleModel model;  // Move is noise-free; the noise is drawn here
  const RayCaster caster(plan);  // the plan's index, taken once for the whole run
  GridSimRun run;
  Pose2 truth = start;
  Pose2 odometry = start;
  for (int k = 0;; ++k) {
    const double t_s = k * params.dt_s;
    LaserScan scan = ScanWith(caster, truth, params.laser, rng);
    scan.t_s = t_s;
    scan.odometry = odometry;
    scan.logged_pose = odometry;  // as in a raw log: the truth goes beside, in run.truth
    run.scans.push_back(std::move(scan));
    run.truth.push_back({t_s, truth});
    if (k >= params.max_steps) break;
    const Control command = controller.Command(truth, params.dt_s);
    if (controller.Done()) break;
    truth = model.Move(truth, command, params.dt_s);
    // The same integration as the truth, so zero noise gives odometry equal to the truth.
    Control measured = command;
    measured[0] += rng.Normal(0.0, params.sigma_v_mps);
    measured[1] += rng.Normal(0.0, params.sigma_omega_radps);
    odometry = model.Move(odometry, measured, params.dt_s);
  }
  return run;
}

}  // namespace slamkit
