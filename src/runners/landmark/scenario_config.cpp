#include "slamkit/runners/landmark/scenario_config.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/config_section.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/landmark_csv.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Describe;
using config::ReadChoice;
using config::Section;

void ReadUniform(const Section& s, UniformWorldParams* p) {
  s.Read("min_xy_m", &p->min_xy_m);
  s.Read("max_xy_m", &p->max_xy_m);
  s.Read("count", &p->count, 0);
  s.Read("density_per_m2", &p->density_per_m2, Bound::kNonNegative);
  if ((p->max_xy_m.array() <= p->min_xy_m.array()).any()) {
    s.Fail("max_xy_m", "must be greater than min_xy_m in x and y");
  }
}

void ReadClusters(const Section& world, std::vector<ClusterParams>* clusters) {
  const YAML::Node list = world.Get("clusters");
  if (!list.IsSequence()) world.Fail("clusters", "expected a sequence, got " + Describe(list));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Section s(list[i], world.file(), fmt::format("world.clusters[{}]", i),
                    {"center_m", "sigma_m", "count", "density_per_m2"});
    ClusterParams c;
    s.Read("center_m", &c.center_m);
    s.Read("sigma_m", &c.sigma_m, Bound::kNonNegative);
    s.Read("count", &c.count, 0);
    s.Read("density_per_m2", &c.density_per_m2, Bound::kNonNegative);
    clusters->push_back(c);
  }
}

void ReadWorld(const Section& root, const std::filesystem::path& dir, WorldSpec* w) {
  const Section s = root.Child("world", {"kind", "seed", "uniform", "clusters", "landmarks_csv"});
  w->kind = static_cast<WorldSpec::Kind>(
      ReadChoice(s, "kind", {"uniform", "clusters", "csv"}, static_cast<int>(w->kind)));
  s.Read("seed", &w->seed);
  ReadUniform(s.Child("uniform", {"min_xy_m", "max_xy_m", "count", "density_per_m2"}), &w->uniform);
  if (s.Has("clusters")) ReadClusters(s, &w->clusters);
  if (w->kind == WorldSpec::Kind::kClusters && w->clusters.empty()) {
    s.Fail("clusters", "kind 'clusters' needs at least one cluster");
  }
  const bool csv = w->kind == WorldSpec::Kind::kGiven;
  if (s.Has("landmarks_csv") != csv) {
    s.Fail(csv ? "kind" : "landmarks_csv", "'landmarks_csv' goes with kind 'csv' (and only it)");
  }
  std::string csv_path;
  s.Read("landmarks_csv", &csv_path);
  if (csv) w->given = ReadLandmarkCsv(dir / csv_path);
}

void ReadVehicle(const Section& root, VehicleParams* v) {
  const Section s =
      root.Child("vehicle", {"motion", "wheelbase_m", "sigma_v_mps", "sigma_steer_deg",
                             "sigma_omega_degps", "sigma_xy_m", "sigma_theta_deg"});
  v->kind = static_cast<MotionKind>(
      ReadChoice(s, "motion", {"unicycle", "car_like", "odometry"}, static_cast<int>(v->kind)));
  s.Read("wheelbase_m", &v->car_like.wheelbase_m, Bound::kPositive);
  s.Read("sigma_v_mps", &v->car_like.sigma_v_mps, Bound::kNonNegative);
  s.Read("sigma_v_mps", &v->unicycle.sigma_v_mps, Bound::kNonNegative);
  s.ReadDegrees("sigma_steer_deg", &v->car_like.sigma_steer_rad, Bound::kNonNegative);
  s.ReadDegrees("sigma_omega_degps", &v->unicycle.sigma_omega_radps, Bound::kNonNegative);
  s.Read("sigma_xy_m", &v->odometry.sigma_xy_m, Bound::kNonNegative);
  s.ReadDegrees("sigma_theta_deg", &v->odometry.sigma_theta_rad, Bound::kNonNegative);
}

void ReadController(const Section& root, ControllerParams* c) {
  const Section s = root.Child("controller", {"speed_mps", "max_steer_deg", "max_steer_rate_degps",
                                              "max_turn_rate_degps", "heading_gain_per_s"});
  s.Read("speed_mps", &c->speed_mps, Bound::kPositive);
  s.ReadDegrees("max_steer_deg", &c->max_steer_rad, Bound::kPositive);
  if (c->max_steer_rad >= DegToRad(90.0)) s.Fail("max_steer_deg", "must be < 90");
  s.ReadDegrees("max_steer_rate_degps", &c->max_steer_rate_radps, Bound::kPositive);
  s.ReadDegrees("max_turn_rate_degps", &c->max_turn_rate_radps, Bound::kPositive);
  s.Read("heading_gain_per_s", &c->heading_gain_per_s, Bound::kPositive);
}

void ReadRoute(const Section& root, RouteParams* r) {
  const Section s = root.Child("route", {"waypoints_m", "loops", "switch_distance_m"});
  if (s.Has("waypoints_m")) {
    const YAML::Node list = s.Get("waypoints_m");
    if (!list.IsSequence()) s.Fail("waypoints_m", "expected a sequence, got " + Describe(list));
    r->waypoints_m.clear();
    for (const YAML::Node& point : list) r->waypoints_m.push_back(s.Point("waypoints_m", point));
  }
  if (root.Has("route") && r->waypoints_m.size() < 2) {
    s.Fail("waypoints_m", "a route needs at least 2 waypoints");
  }
  s.Read("loops", &r->loops, 1);
  s.Read("switch_distance_m", &r->switch_distance_m, Bound::kPositive);
}

void ReadSensor(const Section& root, RangeBearingParams* p, int* period_steps) {
  const Section s = root.Child("sensor", {"max_range_m", "min_range_m", "fov_deg", "sigma_range_m",
                                          "sigma_bearing_deg", "period_steps"});
  s.Read("max_range_m", &p->max_range_m, Bound::kPositive);
  s.Read("min_range_m", &p->min_range_m, Bound::kNonNegative);
  if (p->min_range_m >= p->max_range_m) s.Fail("min_range_m", "must be less than max_range_m");
  s.ReadDegrees("fov_deg", &p->fov_rad, Bound::kPositive);
  if (p->fov_rad > DegToRad(360.0) + 1e-12) s.Fail("fov_deg", "must be <= 360");
  s.Read("sigma_range_m", &p->sigma_range_m, Bound::kPositive);
  s.ReadDegrees("sigma_bearing_deg", &p->sigma_bearing_rad, Bound::kPositive);
  s.Read("period_steps", period_steps, 1);
}

void ReadEkf(const Section& root, EkfSlamParams* p) {
  const Section s = root.Child(
      "ekf", {"known_association", "association", "gate_chi2", "new_landmark_chi2",
              "association_margin_m", "initial_landmark_capacity", "max_joint_tests", "jacobians"});
  bool known = p->known_association();
  s.Read("known_association", &known);
  // The names follow AssociationMethod's order.
  p->association_method = static_cast<AssociationMethod>(
      ReadChoice(s, "association", {"nn", "known", "jcbb", "ml", "gnn"},
                 static_cast<int>(known ? AssociationMethod::kKnown
                                        : AssociationMethod::kNearestNeighbour)));
  if (s.Has("association") && s.Has("known_association") &&
      known != (p->association_method == AssociationMethod::kKnown)) {
    s.Fail("known_association", "contradicts `association`; give one of the two");
  }
  int max_joint_tests = static_cast<int>(p->jcbb.max_joint_tests);
  s.Read("max_joint_tests", &max_joint_tests, 1);
  p->jcbb.max_joint_tests = max_joint_tests;
  s.Read("gate_chi2", &p->association.gate_chi2, Bound::kPositive);
  s.Read("new_landmark_chi2", &p->association.new_landmark_chi2, Bound::kPositive);
  if (p->association.new_landmark_chi2 < p->association.gate_chi2) {
    s.Fail(s.Has("new_landmark_chi2") ? "new_landmark_chi2" : "gate_chi2",
           "new_landmark_chi2 must be >= gate_chi2");
  }
  s.Read("association_margin_m", &p->association_margin_m, Bound::kNonNegative);
  s.Read("initial_landmark_capacity", &p->initial_landmark_capacity, 1);
  // The names follow JacobianEstimates' order.
  p->jacobians = static_cast<JacobianEstimates>(
      ReadChoice(s, "jacobians", {"current", "first_estimates"}, static_cast<int>(p->jacobians)));
}

void ReadPlanner(const Section& root, PlannerConfig* p) {
  const Section s = root.Child("planner", {"kind", "trigger_periods", "k", "kmeans_max_iterations",
                                           "max_detour_periods", "min_cluster_landmarks",
                                           "revisit_radius_m"});
  p->kind = static_cast<PlannerKind>(
      ReadChoice(s, "kind", {"route", "swslam"}, static_cast<int>(p->kind)));
  s.Read("trigger_periods", &p->swslam.trigger_periods, 2);
  s.Read("k", &p->swslam.kmeans.k, 1);
  s.Read("kmeans_max_iterations", &p->swslam.kmeans.max_iterations, 1);
  s.Read("max_detour_periods", &p->swslam.max_detour_periods, 1);
  s.Read("min_cluster_landmarks", &p->swslam.min_cluster_landmarks, 1);
  s.Read("revisit_radius_m", &p->swslam.revisit_radius_m, Bound::kNonNegative);
}

ScenarioConfig ReadScenario(const YAML::Node& yaml, const std::filesystem::path& path) {
  const Section root(yaml, path.string(), "",
                     {"name", "dt_s", "max_steps", "world", "vehicle", "controller", "route",
                      "initial_pose", "sensor", "ekf", "planner"});
  ScenarioConfig config;
  ScenarioParams& p = config.scenario;
  root.Read("name", &p.name);
  root.Read("dt_s", &p.dt_s, Bound::kPositive);
  root.Read("max_steps", &p.max_steps, 1);
  ReadWorld(root, path.parent_path(), &p.world);
  ReadVehicle(root, &p.vehicle);
  ReadController(root, &p.controller);
  ReadRoute(root, &p.route);
  const Section pose = root.Child("initial_pose", {"x_m", "y_m", "theta_deg"});
  Eigen::Vector3d xyt = p.initial_pose.vector();
  pose.Read("x_m", &xyt.x());
  pose.Read("y_m", &xyt.y());
  pose.ReadDegrees("theta_deg", &xyt.z(), Bound::kFinite);
  p.initial_pose = Pose2(xyt);
  ReadSensor(root, &p.sensor, &p.sensor_period_steps);
  ReadEkf(root, &config.ekf);
  ReadPlanner(root, &config.planner);
  // Checked last, so that a mistake elsewhere in a file without a route is reported as such.
  if (p.route.waypoints_m.size() < 2) {
    root.Fail("route", "required (a route of at least 2 waypoints)");
  }
  return config;
}

}  // namespace

ScenarioConfig LoadScenario(const std::filesystem::path& path) {
  return ReadScenario(config::LoadYamlFile(path), path);
}

}  // namespace slamkit
