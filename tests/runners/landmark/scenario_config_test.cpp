#include "slamkit/runners/landmark/scenario_config.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/error.hpp"

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;
using testing::Contains;

const fs::path kConfigs = fs::path(SLAMKIT_SOURCE_DIR) / "configs";
constexpr const char* kRoute = "route: {waypoints_m: [[0, 0], [10, 0]]}\n";

class ScenarioConfigFile : public testing::TempDirTest {
 protected:

  fs::path Write(const std::string& name, const std::string& text) const {
    return WriteFile(name, text);
  }
  // The message of the InputError that loading `text` as bad.yaml raises.
  std::string ErrorOf(const std::string& text) const {
    return testing::InputErrorOf([&] { LoadScenario(Write("bad.yaml", text)); });
  }
};

TEST_F(ScenarioConfigFile, LoadsEveryShippedConfig) {
  int loaded = 0;
  for (const auto& entry : fs::directory_iterator(kConfigs)) {
    if (entry.path().extension() != ".yaml") continue;
    // Suite manifests, the grid and line filters' parameters, exploration experiments and the
    // iSAM runner's parameters and the cooperative configs are not scenarios (their own tests
    // load them).
    const std::string stem = entry.path().stem().string();
    if (stem.ends_with("_suite") || stem.ends_with("_selection") || stem == "grid" ||
        stem == "features" || stem == "victoria_park" || stem == "marine_eo" ||
        stem == "mrclam") {
      continue;
    }
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(LoadScenario(entry.path()));
    ++loaded;
  }
  EXPECT_GE(loaded, 3);
}

// A file that sets every key to a value other than its default.
constexpr const char* kEveryKey = R"(
name: everything
dt_s: 0.5
max_steps: 77
world:
  kind: csv
  seed: 12345678901
  uniform: {min_xy_m: [-1, -2], max_xy_m: [3, 4], count: 5, density_per_m2: 0.5}
  clusters: [{center_m: [7, 8], sigma_m: 2.5, count: 3, density_per_m2: 0.25}]
  landmarks_csv: trees.csv
vehicle: {motion: unicycle, wheelbase_m: 2.5, sigma_v_mps: 0.7, sigma_steer_deg: 2,
          sigma_omega_degps: 4, sigma_xy_m: 0.05, sigma_theta_deg: 0.5}
controller: {speed_mps: 1.5, max_steer_deg: 20, max_steer_rate_degps: 10,
             max_turn_rate_degps: 90, heading_gain_per_s: 3}
route: {waypoints_m: [[0, 0], [5, 0], [5, 5]], loops: 3, switch_distance_m: 0.75}
initial_pose: {x_m: 1, y_m: -1, theta_deg: 90}
sensor: {max_range_m: 12, min_range_m: 0.5, fov_deg: 120, sigma_range_m: 0.2,
         sigma_bearing_deg: 2, period_steps: 3}
ekf: {known_association: true, gate_chi2: 5.99, new_landmark_chi2: 20,
      association_margin_m: 2, initial_landmark_capacity: 16, jacobians: first_estimates}
planner: {kind: swslam, trigger_periods: 4, k: 5, kmeans_max_iterations: 7,
          max_detour_periods: 9}
)";

ScenarioConfig LoadEveryKey(const fs::path& dir) {
  std::ofstream(dir / "trees.csv") << "id,x_m,y_m\n4,1,2\n9,3,4\n";
  std::ofstream(dir / "all.yaml") << kEveryKey;
  return LoadScenario(dir / "all.yaml");
}

TEST_F(ScenarioConfigFile, EveryTopLevelAndWorldKeyReachesItsField) {
  const ScenarioConfig c = LoadEveryKey(dir_);
  const ScenarioParams& p = c.scenario;
  EXPECT_EQ(p.name, "everything");
  EXPECT_EQ(p.dt_s, 0.5);
  EXPECT_EQ(p.max_steps, 77);
  EXPECT_EQ(p.world.kind, WorldSpec::Kind::kGiven);
  EXPECT_EQ(p.world.seed, 12345678901u);
  EXPECT_EQ(p.world.uniform.min_xy_m, Eigen::Vector2d(-1, -2));
  EXPECT_EQ(p.world.uniform.max_xy_m, Eigen::Vector2d(3, 4));
  EXPECT_EQ(p.world.uniform.count, 5);
  EXPECT_EQ(p.world.uniform.density_per_m2, 0.5);
  ASSERT_EQ(p.world.clusters.size(), 1u);
  EXPECT_EQ(p.world.clusters[0].center_m, Eigen::Vector2d(7, 8));
  EXPECT_EQ(p.world.clusters[0].sigma_m, 2.5);
  EXPECT_EQ(p.world.clusters[0].count, 3);
  EXPECT_EQ(p.world.clusters[0].density_per_m2, 0.25);
  ASSERT_EQ(p.world.given.landmarks.size(), 2u);
  EXPECT_EQ(p.world.given.landmarks[1].id, 9);
  EXPECT_EQ(p.world.given.landmarks[1].position_m, Eigen::Vector2d(3, 4));
}

TEST_F(ScenarioConfigFile, EveryVehicleControllerAndRouteKeyReachesItsField) {
  const ScenarioConfig c = LoadEveryKey(dir_);
  const ScenarioParams& p = c.scenario;
  EXPECT_EQ(p.vehicle.kind, MotionKind::kUnicycle);
  EXPECT_EQ(p.vehicle.car_like.wheelbase_m, 2.5);
  EXPECT_EQ(p.vehicle.car_like.sigma_v_mps, 0.7);
  EXPECT_EQ(p.vehicle.unicycle.sigma_v_mps, 0.7);
  EXPECT_DOUBLE_EQ(p.vehicle.car_like.sigma_steer_rad, DegToRad(2));
  EXPECT_DOUBLE_EQ(p.vehicle.unicycle.sigma_omega_radps, DegToRad(4));
  EXPECT_EQ(p.vehicle.odometry.sigma_xy_m, 0.05);
  EXPECT_DOUBLE_EQ(p.vehicle.odometry.sigma_theta_rad, DegToRad(0.5));
  EXPECT_EQ(p.controller.speed_mps, 1.5);
  EXPECT_DOUBLE_EQ(p.controller.max_steer_rad, DegToRad(20));
  EXPECT_DOUBLE_EQ(p.controller.max_steer_rate_radps, DegToRad(10));
  EXPECT_DOUBLE_EQ(p.controller.max_turn_rate_radps, DegToRad(90));
  EXPECT_EQ(p.controller.heading_gain_per_s, 3.0);
  ASSERT_EQ(p.route.waypoints_m.size(), 3u);
  EXPECT_EQ(p.route.waypoints_m[2], Eigen::Vector2d(5, 5));
  EXPECT_EQ(p.route.loops, 3);
  EXPECT_EQ(p.route.switch_distance_m, 0.75);
  EXPECT_EQ(p.initial_pose.x(), 1.0);
  EXPECT_EQ(p.initial_pose.y(), -1.0);
  EXPECT_DOUBLE_EQ(p.initial_pose.theta(), DegToRad(90));
}

TEST_F(ScenarioConfigFile, EverySensorAndEkfKeyReachesItsField) {
  const ScenarioConfig c = LoadEveryKey(dir_);
  const ScenarioParams& p = c.scenario;
  EXPECT_EQ(p.sensor.max_range_m, 12.0);
  EXPECT_EQ(p.sensor.min_range_m, 0.5);
  EXPECT_DOUBLE_EQ(p.sensor.fov_rad, DegToRad(120));
  EXPECT_EQ(p.sensor.sigma_range_m, 0.2);
  EXPECT_DOUBLE_EQ(p.sensor.sigma_bearing_rad, DegToRad(2));
  EXPECT_EQ(p.sensor_period_steps, 3);
  EXPECT_TRUE(c.ekf.known_association());
  EXPECT_EQ(c.ekf.association.gate_chi2, 5.99);
  EXPECT_EQ(c.ekf.association.new_landmark_chi2, 20.0);
  EXPECT_EQ(c.ekf.association_margin_m, 2.0);
  EXPECT_EQ(c.ekf.initial_landmark_capacity, 16);
  EXPECT_EQ(c.ekf.jacobians, JacobianEstimates::kFirstEstimates);
}

TEST_F(ScenarioConfigFile, EveryPlannerKeyReachesItsField) {
  const ScenarioConfig c = LoadEveryKey(dir_);
  EXPECT_EQ(c.planner.kind, PlannerKind::kSwslam);
  EXPECT_EQ(c.planner.swslam.trigger_periods, 4);
  EXPECT_EQ(c.planner.swslam.kmeans.k, 5);
  EXPECT_EQ(c.planner.swslam.kmeans.max_iterations, 7);
  EXPECT_EQ(c.planner.swslam.max_detour_periods, 9);
  const ScenarioConfig route = LoadScenario(Write("route.yaml", kRoute));
  EXPECT_EQ(route.planner.kind, PlannerKind::kRoute);
  EXPECT_EQ(route.planner.swslam.trigger_periods, 3);
}

TEST_F(ScenarioConfigFile, BadPlannerKeysNameFileLineAndKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"planner: {kind: greedy}\n",
       "bad.yaml:2: key 'planner.kind': expected one of route, swslam"},
      {"planner:\n  trigger_periods: 1\n",
       "bad.yaml:3: key 'planner.trigger_periods': must be >= 2"},
      {"planner: {k: 0}\n", "bad.yaml:2: key 'planner.k': must be >= 1"},
      {"planner: {kmeans_max_iterations: 0}\n", "bad.yaml:2: key 'planner.kmeans_max_iterations'"},
      {"planner: {max_detour_periods: 2.5}\n",
       "bad.yaml:2: key 'planner.max_detour_periods': expected an integer"},
      {"planner: {clusters: 3}\n", "bad.yaml:2: unknown key 'clusters' in section 'planner'"},
  };
  for (const auto& [yaml, expected] : cases) {
    EXPECT_TRUE(Contains(ErrorOf(std::string(kRoute) + yaml), expected)) << yaml;
  }
}

TEST_F(ScenarioConfigFile, AbsentKeysKeepTheDefaults) {
  const ScenarioConfig c = LoadScenario(Write("min.yaml", kRoute));
  const ScenarioParams& p = c.scenario;
  const ScenarioConfig dc;
  const ScenarioParams& d = dc.scenario;
  EXPECT_EQ(p.dt_s, d.dt_s);
  EXPECT_EQ(p.max_steps, d.max_steps);
  EXPECT_EQ(p.vehicle.kind, d.vehicle.kind);
  EXPECT_EQ(p.sensor.fov_rad, d.sensor.fov_rad);
  EXPECT_EQ(p.sensor_period_steps, d.sensor_period_steps);
  EXPECT_EQ(c.ekf.association.gate_chi2, dc.ekf.association.gate_chi2);
  EXPECT_EQ(c.ekf.jacobians, JacobianEstimates::kCurrent);
  EXPECT_EQ(p.route.loops, d.route.loops);
}

TEST_F(ScenarioConfigFile, UnknownKeyNamesFileLineAndKey) {
  const std::string root = ErrorOf(std::string("dt_s: 0.1\n") + kRoute + "sensr: {}\n");
  EXPECT_TRUE(Contains(root, "bad.yaml:3: unknown key 'sensr' in section 'root' (known: name,"));
  const std::string nested = ErrorOf(std::string(kRoute) + "sensor:\n  fov_deg: 90\n  rnage: 3\n");
  EXPECT_TRUE(Contains(nested, "bad.yaml:4: unknown key 'rnage' in section 'sensor'"));
  EXPECT_TRUE(Contains(ErrorOf(std::string(kRoute) + "dt_s: 1\nsensor: {}\ndt_s: 2\n"),
                       "bad.yaml:4: duplicate key 'dt_s' (first on line 2)"));
  const std::string cluster = ErrorOf(std::string(kRoute) +
                                      "world:\n  clusters:\n    - {center_m: [0, 0]}\n"
                                      "    - {centre_m: [1, 1]}\n");
  EXPECT_TRUE(
      Contains(cluster, "bad.yaml:5: unknown key 'centre_m' in section 'world.clusters[1]'"));
}

TEST_F(ScenarioConfigFile, WrongTypeNamesFileLineAndKey) {
  const std::string body = std::string("name: x\n") + kRoute;
  EXPECT_TRUE(Contains(ErrorOf(body + "dt_s: abc\n"),
                       "bad.yaml:3: key 'dt_s': expected a number, got 'abc'"));
  EXPECT_TRUE(Contains(ErrorOf(body + "dt_s: 1.5abc\n"),
                       "bad.yaml:3: key 'dt_s': expected a number, got '1.5abc'"));
  EXPECT_TRUE(Contains(ErrorOf(body + "max_steps: 0x10\n"),
                       "bad.yaml:3: key 'max_steps': expected an integer"));
  EXPECT_TRUE(Contains(ErrorOf(body + "sensor:\n  period_steps: 2.5\n"),
                       "bad.yaml:4: key 'sensor.period_steps': expected an integer"));
  EXPECT_TRUE(Contains(ErrorOf(body + "ekf: {known_association: maybe}\n"),
                       "bad.yaml:3: key 'ekf.known_association': expected true or false"));
  EXPECT_TRUE(
      Contains(ErrorOf(body + "sensor: [1, 2]\n"), "bad.yaml:3: key 'sensor': expected a map"));
  EXPECT_TRUE(Contains(ErrorOf(body + "vehicle: {motion: tank}\n"),
                       "bad.yaml:3: key 'vehicle.motion': expected one of unicycle, car_like"));
  EXPECT_TRUE(Contains(ErrorOf("route: {waypoints_m: [[0, 0], [1]]}\n"),
                       "bad.yaml:1: key 'route.waypoints_m': expected a point [x, y]"));
}

TEST_F(ScenarioConfigFile, BadValuesNameFileLineAndKey) {
  const std::string body = std::string(kRoute);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"dt_s: 0\n", "bad.yaml:2: key 'dt_s': must be > 0"},
      {"dt_s: .nan\n", "bad.yaml:2: key 'dt_s': must be a finite number"},
      {"dt_s: -.inf\n", "bad.yaml:2: key 'dt_s': must be a finite number"},
      {"max_steps: 0\n", "bad.yaml:2: key 'max_steps': must be >= 1"},
      {"vehicle:\n  sigma_v_mps: -0.1\n", "bad.yaml:3: key 'vehicle.sigma_v_mps': must be >= 0"},
      {"sensor: {sigma_range_m: 0}\n", "bad.yaml:2: key 'sensor.sigma_range_m': must be > 0"},
      {"sensor: {fov_deg: 400}\n", "bad.yaml:2: key 'sensor.fov_deg': must be <= 360"},
      {"sensor: {min_range_m: 40}\n", "bad.yaml:2: key 'sensor.min_range_m'"},
      {"world: {uniform: {count: -1}}\n", "bad.yaml:2: key 'world.uniform.count': must be >= 0"},
      {"world: {seed: -1}\n", "bad.yaml:2: key 'world.seed'"},
      {"world: {uniform: {max_xy_m: [-9, 9]}}\n", "bad.yaml:2: key 'world.uniform.max_xy_m'"},
      {"world: {kind: clusters}\n", "key 'world.clusters'"},
      {"world: {kind: csv}\n", "bad.yaml:2: key 'world.kind'"},
      {"ekf:\n  gate_chi2: 9\n  new_landmark_chi2: 5\n",
       "bad.yaml:4: key 'ekf.new_landmark_chi2': new_landmark_chi2 must be >= gate_chi2"},
      {"controller: {max_steer_deg: 95}\n", "bad.yaml:2: key 'controller.max_steer_deg'"},
  };
  for (const auto& [yaml, expected] : cases) {
    EXPECT_TRUE(Contains(ErrorOf(body + yaml), expected)) << yaml;
  }
  EXPECT_TRUE(Contains(ErrorOf("route:\n  waypoints_m: [[0, 0], [1, 1]]\n  loops: 0\n"),
                       "bad.yaml:3: key 'route.loops': must be >= 1"));
  EXPECT_TRUE(Contains(ErrorOf("route:\n  waypoints_m: [[0, 0]]\n"),
                       "bad.yaml:2: key 'route.waypoints_m': a route needs at least 2 waypoints"));
  EXPECT_TRUE(Contains(ErrorOf("dt_s: 0.1\n"), "bad.yaml: key 'route': required"));
}

// Found by fuzz/scenario_fuzzer.cpp's check that every value is finite: a `_deg` value above
// about 5.7e307 is finite, but deg·π overflows, so it used to become an infinite angle in radians.
TEST_F(ScenarioConfigFile, DegreesTooLargeForRadiansNameFileLineAndKey) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"vehicle: {sigma_steer_deg: 1e308}\n",
       "bad.yaml:2: key 'vehicle.sigma_steer_deg': too large to convert to radians, got '1e308'"},
      {"vehicle:\n  sigma_theta_deg: 6e307\n", "bad.yaml:3: key 'vehicle.sigma_theta_deg'"},
      {"controller: {max_turn_rate_degps: 1.7e308}\n",
       "bad.yaml:2: key 'controller.max_turn_rate_degps': too large"},
      {"sensor: {sigma_bearing_deg: 1e308}\n", "bad.yaml:2: key 'sensor.sigma_bearing_deg'"},
      {"initial_pose: {theta_deg: -1e308}\n", "bad.yaml:2: key 'initial_pose.theta_deg'"},
  };
  for (const auto& [yaml, expected] : cases) {
    EXPECT_TRUE(Contains(ErrorOf(std::string(kRoute) + yaml), expected)) << yaml;
  }
  // Large but convertible values are still read.
  const ScenarioConfig config =
      LoadScenario(Write("ok.yaml", std::string(kRoute) + "vehicle: {sigma_steer_deg: 1e300}\n"));
  EXPECT_DOUBLE_EQ(config.scenario.vehicle.car_like.sigma_steer_rad, DegToRad(1e300));
}

// Issue 8 item 5: yaml-cpp reads a whole stream; /dev/zero never ends.
TEST_F(ScenarioConfigFile, ADeviceIsNotAConfigFile) {
  const std::string message = testing::InputErrorOf([] { LoadScenario("/dev/zero"); });
  EXPECT_NE(message.find("/dev/zero: not a regular file"), std::string::npos) << message;
}

TEST_F(ScenarioConfigFile, FileProblemsNameTheFile) {
  EXPECT_TRUE(Contains(ErrorOf("route: {waypoints_m: [[0, 0], [1, 1]\n"), "bad.yaml:"));
  try {
    LoadScenario(dir_ / "absent.yaml");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_TRUE(Contains(e.what(), "absent.yaml"));
  }
  // landmarks_csv is read relative to the YAML file, and its errors name the CSV file.
  fs::create_directories(dir_ / "sub");
  std::ofstream(dir_ / "sub" / "trees.csv") << "0,1,nan\n";
  std::ofstream(dir_ / "sub" / "w.yaml")
      << kRoute << "world: {kind: csv, landmarks_csv: trees.csv}\n";
  try {
    LoadScenario(dir_ / "sub" / "w.yaml");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_TRUE(Contains(e.what(), "trees.csv:1: field 'y_m'"));
  }
}

}  // namespace
}  // namespace slamkit
