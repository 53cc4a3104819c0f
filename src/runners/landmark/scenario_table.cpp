// The scenario file's table: every scalar key of configs/*.yaml (docs/scenario.md). The lists,
// the landmark file, the start pose and the checks between keys are read beside it
// (scenario_config.cpp).

#include "slamkit/runners/landmark/fastslam_sampling.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Degrees;
using config::Integer;
using config::Number;
using config::ParamTable;

constexpr Bound kScenarioNonNeg = Bound::kNonNegative;
constexpr Bound kScenarioPos = Bound::kPositive;

void AddScenarioVehicle(VehicleParams& v, ControllerParams& c, ParamTable& t) {
  const std::string s = "vehicle";
  const ParamTable lines = {
      config::Choice(s, "motion", &v.kind, {"unicycle", "car_like", "odometry"},
                     "the vehicle's motion model"),
      Number(s, "wheelbase_m", &v.car_like.wheelbase_m, kScenarioPos, "m", "car-like wheelbase"),
      // The unicycle's too (scenario_config.cpp).
      Number(s, "sigma_v_mps", &v.car_like.sigma_v_mps, kScenarioNonNeg, "m/s", "speed noise"),
      Degrees(s, "sigma_steer_deg", &v.car_like.sigma_steer_rad, kScenarioNonNeg, "deg",
              "steering noise"),
      Degrees(s, "sigma_omega_degps", &v.unicycle.sigma_omega_radps, kScenarioNonNeg, "deg/s",
              "unicycle turn-rate noise"),
      Number(s, "sigma_xy_m", &v.odometry.sigma_xy_m, kScenarioNonNeg, "m", "odometry noise"),
      Degrees(s, "sigma_theta_deg", &v.odometry.sigma_theta_rad, kScenarioNonNeg, "deg",
              "odometry heading noise"),
      Number("controller", "speed_mps", &c.speed_mps, kScenarioPos, "m/s", "driving speed"),
      Degrees("controller", "max_steer_deg", &c.max_steer_rad, kScenarioPos, "deg",
              "steering limit (< 90)"),
      Degrees("controller", "max_steer_rate_degps", &c.max_steer_rate_radps, kScenarioPos, "deg/s",
              "steering rate limit"),
      Degrees("controller", "max_turn_rate_degps", &c.max_turn_rate_radps, kScenarioPos, "deg/s",
              "unicycle turn-rate limit"),
      Number("controller", "heading_gain_per_s", &c.heading_gain_per_s, kScenarioPos, "1/s",
             "heading error to turn rate"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddScenarioRoute(ScenarioParams& p, ParamTable& t) {
  RangeBearingParams& z = p.sensor;
  const ParamTable lines = {
      config::Listed("route", "waypoints_m", "the route: [[x, y], ...], at least 2"),
      Integer("route", "loops", &p.route.loops, 1, "times round the route"),
      Number("route", "switch_distance_m", &p.route.switch_distance_m, kScenarioPos, "m",
             "a waypoint is reached within this"),
      config::Listed("initial_pose", "x_m", "start x [m]"),
      config::Listed("initial_pose", "y_m", "start y [m]"),
      config::Listed("initial_pose", "theta_deg", "start heading [deg]"),
      Number("sensor", "max_range_m", &z.max_range_m, kScenarioPos, "m", "sensor range"),
      Number("sensor", "min_range_m", &z.min_range_m, kScenarioNonNeg, "m", "blind range"),
      Degrees("sensor", "fov_deg", &z.fov_rad, kScenarioPos, "deg", "field of view (<= 360)"),
      Number("sensor", "sigma_range_m", &z.sigma_range_m, kScenarioPos, "m", "range noise"),
      Degrees("sensor", "sigma_bearing_deg", &z.sigma_bearing_rad, kScenarioPos, "deg",
              "bearing noise"),
      Integer("sensor", "period_steps", &p.sensor_period_steps, 1, "observe every this many"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddScenarioPlanner(PlannerConfig& p, ParamTable& t) {
  const std::string s = "planner";
  SwslamPlannerParams& w = p.swslam;
  const ParamTable lines = {
      config::Choice(s, "kind", &p.kind, {"route", "swslam"}, "who picks the next waypoint"),
      Integer(s, "trigger_periods", &w.trigger_periods, 2, "area-of-interest trigger"),
      Integer(s, "k", &w.kmeans.k, 1, "K-means clusters"),
      Integer(s, "kmeans_max_iterations", &w.kmeans.max_iterations, 1, "K-means iterations"),
      Integer(s, "max_detour_periods", &w.max_detour_periods, 1, "a detour's longest"),
      Integer(s, "min_cluster_landmarks", &w.min_cluster_landmarks, 1,
              "fewest landmarks of a cluster worth a detour"),
      Number(s, "revisit_radius_m", &w.revisit_radius_m, kScenarioNonNeg, "m",
             "a cluster within this of a visited one is not revisited"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

}  // namespace

void AddScenarioWorldLines(WorldSpec& w, ParamTable& t) {
  const ParamTable lines = {
      config::Choice("world", "kind", &w.kind, {"uniform", "clusters", "csv"},
                     "where the landmarks come from"),
      config::Seed("world", "seed", &w.seed, "random seed of the landmarks"),
      config::Listed("world", "clusters", "kind clusters: [{center_m, sigma_m, count, ...}]"),
      config::Listed("world", "landmarks_csv", "kind csv: the landmark file (id,x_m,y_m)"),
      config::Point("world.uniform", "min_xy_m", &w.uniform.min_xy_m, "the area's low corner"),
      config::Point("world.uniform", "max_xy_m", &w.uniform.max_xy_m, "the area's high corner"),
      Integer("world.uniform", "count", &w.uniform.count, 0, "landmarks (0: by density)"),
      Number("world.uniform", "density_per_m2", &w.uniform.density_per_m2, kScenarioNonNeg, "1/m^2",
             "landmarks per square metre"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddScenarioEkfLines(EkfSlamParams& e, ParamTable& t) {
  const std::string s = "ekf";
  const ParamTable lines = {
      config::Listed(s, "known_association", "the same as association: known (or nn)"),
      // The names follow AssociationMethod's order.
      config::Choice(s, "association", &e.association_method, {"nn", "known", "jcbb", "ml", "gnn"},
                     "data association"),
      Number(s, "gate_chi2", &e.association.gate_chi2, kScenarioPos, "",
             "a sighting matches a landmark within this chi-square"),
      Number(s, "new_landmark_chi2", &e.association.new_landmark_chi2, kScenarioPos, "",
             "a sighting beyond this from every landmark is a new one"),
      Number(s, "association_margin_m", &e.association_margin_m, kScenarioNonNeg, "m",
             "landmarks considered beyond the sensor's range"),
      Integer(s, "initial_landmark_capacity", &e.initial_landmark_capacity, 1,
              "landmarks the state has room for at first"),
      Integer(s, "max_joint_tests", &e.jcbb.max_joint_tests, 1,
              "JCBB: most joint-compatibility tests a scan may take"),
      // The names follow JacobianEstimates' order.
      config::Choice(s, "jacobians", &e.jacobians, {"current", "first_estimates"},
                     "where the Jacobians are evaluated"),
      // The names follow EkfUpdateMode's order.
      config::Choice(s, "update", &e.update, {"dense", "compressed"},
                     "compressed: updates touch the active area only (Guivant & Nebot 2001)"),
      Number(s, "area_hysteresis", &e.active_area.hysteresis_fraction, kScenarioPos, "",
             "compressed: a new area when the vehicle is this fraction of its reach away"),
      Number(s, "area_sigma_factor", &e.active_area.sigma_factor, kScenarioNonNeg, "",
             "compressed: the area widened by this many position sigmas"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

config::ParamTable ScenarioParamTable(ScenarioConfig& config) {
  ScenarioParams& p = config.scenario;
  ParamTable t = {
      config::Text("", "name", &p.name, "the scenario's name"),
      Number("", "dt_s", &p.dt_s, kScenarioPos, "s", "simulation step"),
      Integer("", "max_steps", &p.max_steps, 1, "stop after this many steps"),
  };
  AddScenarioWorldLines(p.world, t);
  AddScenarioVehicle(p.vehicle, p.controller, t);
  AddScenarioRoute(p, t);
  AddScenarioEkfLines(config.ekf, t);
  AddScenarioPlanner(config.planner, t);
  AddDelayedSamplingLines("fastslam", &config.fastslam.delayed_sampling,
                          &config.fastslam.window_max_landmarks, &t);
  return t;
}

}  // namespace slamkit
