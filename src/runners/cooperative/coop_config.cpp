// The cooperative config file: one table for its scalar keys, the vehicles read beside it.
#include "slamkit/runners/cooperative/coop_config.hpp"

#include <cmath>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/config_section.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Degrees;
using config::Integer;
using config::Number;
using config::ParamTable;

void AddSensorLines(const std::string& s, RangeBearingParams& z, ParamTable& t) {
  const ParamTable lines = {
      Number(s, "max_range_m", &z.max_range_m, Bound::kPositive, "m", "sensor range"),
      Number(s, "sigma_range_m", &z.sigma_range_m, Bound::kPositive, "m", "range noise"),
      Degrees(s, "sigma_bearing_deg", &z.sigma_bearing_rad, Bound::kPositive, "deg",
              "bearing noise"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddFilterLines(CoopFilterParams& f, ParamTable& t) {
  const std::string s = "filter";
  const ParamTable lines = {
      Number(s, "sigma_v_mps", &f.motion.sigma_v_mps, Bound::kNonNegative, "m/s",
             "the filters' speed noise per control"),
      Degrees(s, "sigma_omega_degps", &f.motion.sigma_omega_radps, Bound::kNonNegative, "deg/s",
              "the filters' turn-rate noise per control"),
      config::Listed(s, "control_noise_density",
                     "[m^2/s, deg^2/s]: the control noise per second instead (real logs)"),
      config::Flag(s, "known_association", &f.known_association,
                   "sightings keep their landmark ids"),
      Number(s, "extended_max_age_s", &f.filter.extended_max_age_s, Bound::kNonNegative, "s",
             "eo: the oldest v-v sighting that may extend a scan"),
      config::Flag(s, "extended_heading_noise", &f.filter.extended_heading_noise,
                   "eo: R^e includes the relative heading's variance"),
      config::Limit(s, "known_gate_chi2", &f.known_gate_chi2, "",
                    "known ids: sightings beyond this chi-square are outliers (null: none)",
                    Bound::kPositive),
      config::Limit(s, "vehicle_gate_chi2", &f.filter.vehicle_gate_chi2, "",
                    "v-v sightings beyond this chi-square are not used (null: none)",
                    Bound::kPositive),
      Number(s, "record_period_s", &f.record_period_s, Bound::kNonNegative, "s",
             "estimates recorded at most this often"),
      Number("messages", "loss_probability", &f.messages.loss_probability, Bound::kNonNegative,
             "", "each sighting message is lost with this probability"),
      Integer("messages", "max_sightings", &f.messages.max_sightings, 0,
              "the nearest this many sightings per message (0: all)"),
      Number("messages", "delay_s", &f.messages.delay_s, Bound::kNonNegative, "s",
             "every message arrives at most this late; eo and eo-exact filters run this far "
             "behind and move their own pose on by its controls"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

// `vehicles: [{start: [x_m, y_m, theta_deg], waypoints_m: [[x, y], ...]}, ...]`.
void ReadVehicles(const config::Section& root, const RouteParams& route,
                  std::vector<FleetVehicleSpec>* vehicles) {
  if (!root.Has("vehicles")) return;
  const YAML::Node list = root.Get("vehicles");
  if (!list.IsSequence()) root.Fail("vehicles", "expected a sequence, got " + config::Describe(list));
  for (std::size_t i = 0; i < list.size(); ++i) {
    const config::Section v(list[i], root.file(), fmt::format("vehicles[{}]", i),
                            {"start", "waypoints_m"});
    const YAML::Node start = v.Get("start");
    if (!start.IsSequence() || start.size() != 3) {
      v.Fail("start", "expected [x_m, y_m, theta_deg]");
    }
    FleetVehicleSpec spec;
    spec.start = Pose2(v.Number("start", start[0], Bound::kFinite),
                       v.Number("start", start[1], Bound::kFinite),
                       DegToRad(v.Number("start", start[2], Bound::kFinite)));
    spec.route = route;
    const YAML::Node points = v.Get("waypoints_m");
    if (!points.IsSequence() || points.size() < 2) {
      v.Fail("waypoints_m", "a route needs at least 2 waypoints");
    }
    for (const YAML::Node& p : points) spec.route.waypoints_m.push_back(v.Point("waypoints_m", p));
    vehicles->push_back(spec);
  }
}

void ReadDensity(const config::Section& filter, CoopFilterParams* f) {
  if (!filter.Has("control_noise_density")) return;
  const YAML::Node d = filter.Get("control_noise_density");
  if (!d.IsSequence() || d.size() != 2) {
    filter.Fail("control_noise_density", "expected [m^2/s, deg^2/s]");
  }
  const double v = filter.Number("control_noise_density", d[0], Bound::kPositive);
  const double w = filter.Number("control_noise_density", d[1], Bound::kPositive);
  f->control_noise_density = Eigen::Vector2d(v, w * std::pow(DegToRad(1.0), 2));
}

}  // namespace

config::ParamTable CoopParamTable(CoopConfig& c) {
  FleetScenarioParams& p = c.scenario;
  ParamTable t = {
      config::Text("", "name", &p.name, "the run's name"),
      Number("", "dt_s", &p.dt_s, Bound::kPositive, "s", "simulation step"),
      Integer("", "max_steps", &p.max_steps, 1, "stop after this many steps"),
      config::WithFlag(Integer("", "runs", &c.runs, 1, "Monte Carlo runs"), "--runs"),
      config::WithFlag(config::Seed("", "seed", &c.seed, "random seed of the runs"), "--seed"),
      config::Listed("", "vehicles", "[{start: [x_m, y_m, theta_deg], waypoints_m: [...]}]"),
      Integer("route", "loops", &c.route.loops, 1, "times round each route"),
      Number("route", "switch_distance_m", &c.route.switch_distance_m, Bound::kPositive, "m",
             "a waypoint is reached within this"),
      Number("motion", "sigma_v_mps", &p.motion.sigma_v_mps, Bound::kNonNegative, "m/s",
             "the true controls' speed noise"),
      Degrees("motion", "sigma_omega_degps", &p.motion.sigma_omega_radps, Bound::kNonNegative,
              "deg/s", "the true controls' turn-rate noise"),
      Number("controller", "speed_mps", &p.controller.speed_mps, Bound::kPositive, "m/s",
             "driving speed"),
      Degrees("controller", "max_turn_rate_degps", &p.controller.max_turn_rate_radps,
              Bound::kPositive, "deg/s", "turn-rate limit"),
      Number("controller", "heading_gain_per_s", &p.controller.heading_gain_per_s,
             Bound::kPositive, "1/s", "heading error to turn rate"),
      Integer("sensor", "period_steps", &p.sensor_period_steps, 1, "sense every this many steps"),
  };
  AddScenarioWorldLines(p.world, t);
  AddSensorLines("sensor", p.sensor, t);
  AddSensorLines("vehicle_sensor", p.vehicle_sensor, t);
  AddScenarioEkfLines(c.filter.filter.ekf, t);
  AddFilterLines(c.filter, t);
  return t;
}

CoopConfig LoadCoopConfig(const std::filesystem::path& path) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  CoopConfig c;
  const config::ParamTable table = CoopParamTable(c);
  config::ReadParams(yaml, path.string(), table);
  ReadScenarioWorld(yaml, path, table, &c.scenario.world);
  ReadVehicles(config::TableSection(yaml, path.string(), table, ""), c.route, &c.scenario.vehicles);
  ReadDensity(config::TableSection(yaml, path.string(), table, "filter"), &c.filter);
  // Without ids the known-id associator would make every sighting a new landmark.
  if (!c.filter.known_association &&
      c.filter.filter.ekf.association_method == AssociationMethod::kKnown) {
    config::TableSection(yaml, path.string(), table, "filter")
        .Fail("known_association", "is false, but ekf.association is known: set ekf.association "
                                   "to nn, ml, gnn or jcbb");
  }
  if (c.filter.filter.ekf.update != EkfUpdateMode::kDense) {
    config::TableSection(yaml, path.string(), table, "ekf")
        .Fail("update", "is compressed, which only the single-vehicle EKF offers (slamkit mc, "
                        "slamkit run): set it to dense");
  }
  // The filters' sensors are the true ones: the same noise and range (a real log's are the
  // config's own statement of them).
  c.filter.sensor = c.scenario.sensor;
  c.filter.vehicle_sensor = c.scenario.vehicle_sensor;
  return c;
}

nlohmann::json CoopConfigJson(CoopConfig config) {
  nlohmann::json j = config::ParamsJson(CoopParamTable(config));
  nlohmann::json vehicles = nlohmann::json::array();
  for (const FleetVehicleSpec& v : config.scenario.vehicles) {
    nlohmann::json points = nlohmann::json::array();
    for (const Eigen::Vector2d& w : v.route.waypoints_m) points.push_back({w.x(), w.y()});
    vehicles.push_back({{"start", {v.start.x(), v.start.y(), RadToDeg(v.start.theta())}},
                        {"waypoints_m", points}});
  }
  j["vehicles"] = vehicles;
  if (config.filter.control_noise_density) {
    const Eigen::Vector2d d = *config.filter.control_noise_density;
    j["filter"]["control_noise_density"] = {d.x(), d.y() / std::pow(DegToRad(1.0), 2)};
  }
  return j;
}

}  // namespace slamkit
