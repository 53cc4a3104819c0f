#include "slamkit/io/scenario_config.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/landmark_csv.hpp"

namespace slamkit {
namespace {

enum class Bound { kFinite, kNonNegative, kPositive };

std::string Describe(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a sequence";
  if (node.IsMap()) return "a map";
  return "nothing";
}

// A YAML number; yaml-cpp's conversion also accepts the YAML spellings of infinity and NaN
// (`.inf`, `.nan`), which the callers reject as non-finite with their own message.
std::optional<double> ParseNumber(const YAML::Node& node) {
  double value = 0.0;
  if (!YAML::convert<double>::decode(node, value)) return std::nullopt;
  return value;
}

template <typename T>
std::optional<T> ParseInteger(const YAML::Node& node) {
  if (!node.IsScalar()) return std::nullopt;
  const std::string& text = node.Scalar();
  T value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// One YAML map of the config: checks its keys against the known ones and reads typed values,
// leaving the output untouched when a key is absent. Errors name the file, line and key path.
class Section {
 public:
  Section(const YAML::Node& node, std::string file, std::string path,
          std::vector<std::string> known)
      : node_(node), file_(std::move(file)), path_(std::move(path)) {
    if (!node_.IsNull() && !node_.IsMap()) {
      FailAt(node_,
             fmt::format("{}: expected a map, got {}",
                         path_.empty() ? "the file" : "key '" + path_ + "'", Describe(node_)));
    }
    if (node_.IsMap()) CheckKeys(known);
  }

  bool Has(const std::string& key) const { return line_of_key_.count(key) > 0; }
  YAML::Node Get(const std::string& key) const { return node_[key]; }
  Section Child(const std::string& key, std::vector<std::string> known) const {
    const YAML::Node child = Has(key) ? Get(key) : YAML::Node();
    return Section(child, file_, Path(key), std::move(known));
  }
  std::string Path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  const std::string& file() const { return file_; }

  [[noreturn]] void Fail(const std::string& key, const std::string& reason) const {
    const auto it = line_of_key_.find(key);
    const std::string line = it == line_of_key_.end() ? "" : fmt::format("{}:", it->second);
    throw InputError(fmt::format("{}:{} key '{}': {}", file_, line, Path(key), reason));
  }
  [[noreturn]] void FailAt(const YAML::Node& at, const std::string& message) const {
    throw InputError(fmt::format("{}:{}: {}", file_, at.Mark().line + 1, message));
  }

  double Number(const std::string& key, const YAML::Node& value, Bound bound) const {
    const std::optional<double> v = ParseNumber(value);
    if (!v) Fail(key, "expected a number, got " + Describe(value));
    if (!std::isfinite(*v)) Fail(key, "must be a finite number, got " + Describe(value));
    if (bound == Bound::kPositive && *v <= 0.0) Fail(key, fmt::format("must be > 0, got {}", *v));
    if (bound == Bound::kNonNegative && *v < 0.0) {
      Fail(key, fmt::format("must be >= 0, got {}", *v));
    }
    return *v;
  }
  void Read(const std::string& key, double* out, Bound bound = Bound::kFinite) const {
    if (Has(key)) *out = Number(key, Get(key), bound);
  }
  void ReadDegrees(const std::string& key, double* out_rad, Bound bound) const {
    if (Has(key)) *out_rad = DegToRad(Number(key, Get(key), bound));
  }
  void Read(const std::string& key, int* out, int min) const {
    if (!Has(key)) return;
    const std::optional<int> v = ParseInteger<int>(Get(key));
    if (!v) Fail(key, "expected an integer, got " + Describe(Get(key)));
    if (*v < min) Fail(key, fmt::format("must be >= {}, got {}", min, *v));
    *out = *v;
  }
  void Read(const std::string& key, std::uint64_t* out) const {
    if (!Has(key)) return;
    const std::optional<std::uint64_t> v = ParseInteger<std::uint64_t>(Get(key));
    if (!v) Fail(key, "expected a non-negative integer, got " + Describe(Get(key)));
    *out = *v;
  }
  void Read(const std::string& key, bool* out) const {
    if (Has(key) && !YAML::convert<bool>::decode(Get(key), *out)) {
      Fail(key, "expected true or false, got " + Describe(Get(key)));
    }
  }
  void Read(const std::string& key, std::string* out) const {
    if (!Has(key)) return;
    if (!Get(key).IsScalar()) Fail(key, "expected a string, got " + Describe(Get(key)));
    *out = Get(key).Scalar();
  }
  // An [x, y] pair in metres.
  Eigen::Vector2d Point(const std::string& key, const YAML::Node& value) const {
    if (!value.IsSequence() || value.size() != 2) {
      Fail(key, "expected a point [x, y], got " + Describe(value));
    }
    return {Number(key, value[0], Bound::kFinite), Number(key, value[1], Bound::kFinite)};
  }
  void Read(const std::string& key, Eigen::Vector2d* out) const {
    if (Has(key)) *out = Point(key, Get(key));
  }

 private:
  void CheckKeys(const std::vector<std::string>& known) {
    for (const auto& entry : node_) {
      const std::string key = entry.first.Scalar();
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        FailAt(entry.first, fmt::format("unknown key '{}' in section '{}' (known: {})", key,
                                        path_.empty() ? "root" : path_, fmt::join(known, ", ")));
      }
      const auto [it, inserted] = line_of_key_.emplace(key, entry.first.Mark().line + 1);
      if (!inserted) {
        FailAt(entry.first,
               fmt::format("duplicate key '{}' (first on line {})", Path(key), it->second));
      }
    }
  }

  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::map<std::string, int> line_of_key_;
};

// Reads `key` as one of `names` (whose index is the returned value).
int ReadChoice(const Section& s, const std::string& key, const std::vector<std::string>& names,
               int fallback) {
  std::string value;
  s.Read(key, &value);
  if (!s.Has(key)) return fallback;
  const auto it = std::find(names.begin(), names.end(), value);
  if (it == names.end()) {
    s.Fail(key, fmt::format("expected one of {}, got '{}'", fmt::join(names, ", "), value));
  }
  return static_cast<int>(it - names.begin());
}

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
  const Section s = root.Child("ekf", {"known_association", "gate_chi2", "new_landmark_chi2",
                                       "association_margin_m", "initial_landmark_capacity"});
  s.Read("known_association", &p->known_association);
  s.Read("gate_chi2", &p->association.gate_chi2, Bound::kPositive);
  s.Read("new_landmark_chi2", &p->association.new_landmark_chi2, Bound::kPositive);
  if (p->association.new_landmark_chi2 < p->association.gate_chi2) {
    s.Fail(s.Has("new_landmark_chi2") ? "new_landmark_chi2" : "gate_chi2",
           "new_landmark_chi2 must be >= gate_chi2");
  }
  s.Read("association_margin_m", &p->association_margin_m, Bound::kNonNegative);
  s.Read("initial_landmark_capacity", &p->initial_landmark_capacity, 1);
}

ScenarioParams ReadScenario(const YAML::Node& yaml, const std::filesystem::path& path) {
  const Section root(yaml, path.string(), "",
                     {"name", "dt_s", "max_steps", "world", "vehicle", "controller", "route",
                      "initial_pose", "sensor", "ekf"});
  ScenarioParams p;
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
  ReadEkf(root, &p.ekf);
  // Checked last, so that a mistake elsewhere in a file without a route is reported as such.
  if (p.route.waypoints_m.size() < 2) {
    root.Fail("route", "required (a route of at least 2 waypoints)");
  }
  return p;
}

}  // namespace

ScenarioParams LoadScenario(const std::filesystem::path& path) {
  YAML::Node yaml;
  try {
    yaml = YAML::LoadFile(path.string());
  } catch (const YAML::BadFile&) {
    throw InputError(path.string() + ": cannot open file");
  } catch (const YAML::ParserException& e) {
    throw InputError(
        fmt::format("{}:{}: YAML syntax error: {}", path.string(), e.mark.line + 1, e.msg));
  }
  return ReadScenario(yaml, path);
}

}  // namespace slamkit
