#include "slamkit/runners/landmark/scenario_config.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/config_section.hpp"
#include "slamkit/io/landmark_csv.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Describe;
using config::Section;

void CheckUniform(const Section& s, const UniformWorldParams& p) {
  if ((p.max_xy_m.array() <= p.min_xy_m.array()).any()) {
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

void ReadWorldLists(const Section& s, const std::filesystem::path& dir, WorldSpec* w) {
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

void CheckMotion(const Section& vehicle, const Section& controller, ScenarioParams* p) {
  // One key for both speed noises: the table reads it into the car's.
  if (vehicle.Has("sigma_v_mps")) {
    p->vehicle.unicycle.sigma_v_mps = p->vehicle.car_like.sigma_v_mps;
  }
  if (p->controller.max_steer_rad >= DegToRad(90.0)) {
    controller.Fail("max_steer_deg", "must be < 90");
  }
}

void ReadWaypoints(const Section& s, bool given, RouteParams* r) {
  if (s.Has("waypoints_m")) {
    const YAML::Node list = s.Get("waypoints_m");
    if (!list.IsSequence()) s.Fail("waypoints_m", "expected a sequence, got " + Describe(list));
    r->waypoints_m.clear();
    for (const YAML::Node& point : list) r->waypoints_m.push_back(s.Point("waypoints_m", point));
  }
  if (given && r->waypoints_m.size() < 2) {
    s.Fail("waypoints_m", "a route needs at least 2 waypoints");
  }
}

void ReadInitialPose(const Section& pose, Pose2* initial_pose) {
  Eigen::Vector3d xyt = initial_pose->vector();
  pose.Read("x_m", &xyt.x());
  pose.Read("y_m", &xyt.y());
  pose.ReadDegrees("theta_deg", &xyt.z(), Bound::kFinite);
  *initial_pose = Pose2(xyt);
}

void CheckSensor(const Section& s, const RangeBearingParams& p) {
  if (p.min_range_m >= p.max_range_m) s.Fail("min_range_m", "must be less than max_range_m");
  if (p.fov_rad > DegToRad(360.0) + 1e-12) s.Fail("fov_deg", "must be <= 360");
}

// `known_association` is `association: known` (or nn) in the files written before it.
void ReadKnownAssociation(const Section& s, bool known_default, EkfSlamParams* p) {
  bool known = known_default;
  s.Read("known_association", &known);
  if (!s.Has("association")) {
    p->association_method =
        known ? AssociationMethod::kKnown : AssociationMethod::kNearestNeighbour;
  } else if (s.Has("known_association") &&
             known != (p->association_method == AssociationMethod::kKnown)) {
    s.Fail("known_association", "contradicts `association`; give one of the two");
  }
  if (p->association.new_landmark_chi2 < p->association.gate_chi2) {
    s.Fail(s.Has("new_landmark_chi2") ? "new_landmark_chi2" : "gate_chi2",
           "new_landmark_chi2 must be >= gate_chi2");
  }
}

// The keys the table lists but does not read, and the checks between keys.
void ReadBesideTable(const YAML::Node& yaml, const std::filesystem::path& path,
                     const config::ParamTable& table, bool known_default, ScenarioConfig* c) {
  const auto at = [&](const std::string& section) {
    return config::TableSection(yaml, path.string(), table, section);
  };
  ScenarioParams& p = c->scenario;
  ReadScenarioWorld(yaml, path, table, &p.world);
  CheckMotion(at("vehicle"), at("controller"), &p);
  const Section root = at("");
  ReadWaypoints(at("route"), root.Has("route"), &p.route);
  ReadInitialPose(at("initial_pose"), &p.initial_pose);
  CheckSensor(at("sensor"), p.sensor);
  ReadKnownAssociation(at("ekf"), known_default, &c->ekf);
  // Checked last, so that a mistake elsewhere in a file without a route is reported as such.
  if (p.route.waypoints_m.size() < 2) {
    root.Fail("route", "required (a route of at least 2 waypoints)");
  }
}

}  // namespace

void ReadScenarioWorld(const YAML::Node& yaml, const std::filesystem::path& path,
                       const config::ParamTable& table, WorldSpec* world) {
  CheckUniform(config::TableSection(yaml, path.string(), table, "world.uniform"), world->uniform);
  ReadWorldLists(config::TableSection(yaml, path.string(), table, "world"), path.parent_path(),
                 world);
}

nlohmann::json ScenarioParamsJson(const ScenarioConfig& config) {
  ScenarioConfig copy = config;
  nlohmann::json j = config::ParamsJson(ScenarioParamTable(copy));
  j["ekf"]["known_association"] = config.ekf.known_association();
  return j;
}

ScenarioConfig LoadScenario(const std::filesystem::path& path) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  ScenarioConfig config;
  const bool known_default = config.ekf.known_association();
  const config::ParamTable table = ScenarioParamTable(config);
  config::ReadParams(yaml, path.string(), table);
  ReadBesideTable(yaml, path, table, known_default, &config);
  return config;
}

}  // namespace slamkit
