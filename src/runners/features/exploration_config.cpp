#include "slamkit/runners/features/exploration_config.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <string>
#include <vector>

#include "slamkit/io/config_section.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Describe;
using config::Section;

const std::vector<std::string> kTimings = {"modelled", "wall"};
const std::vector<std::string> kPolicies = {"all", "entropy", "entropy-fast", "covariance"};

Pose2 ReadStart(const Section& s) {
  if (!s.Has("start")) return Pose2();
  const YAML::Node v = s.Get("start");
  if (!v.IsSequence() || v.size() != 3) {
    s.Fail("start", "expected [x_m, y_m, theta_rad], got " + Describe(v));
  }
  return Pose2(s.Number("start", v[0], Bound::kFinite), s.Number("start", v[1], Bound::kFinite),
               s.Number("start", v[2], Bound::kFinite));
}

void ReadLaser(const Section& s, LaserSimParams* laser) {
  s.Read("beams", &laser->beams, 2);
  s.Read("range_m", &laser->range_limit_m, Bound::kPositive);
  laser->max_range_m = laser->range_limit_m;  // no-return beams read the range, as the seed's
  s.Read("sigma_range_m", &laser->sigma_range_m, Bound::kNonNegative);
}

void ReadSelection(const Section& s, FeatureSlamParams* slam) {
  slam->selection = static_cast<SelectionKind>(
      config::ReadChoice(s, "policy", kPolicies, static_cast<int>(slam->selection)));
  s.Read("k_max", &slam->covariance.k_max, 1);
  s.Read("min_gain_nats", &slam->entropy.min_gain_nats, Bound::kNonNegative);
}

}  // namespace

ExplorationConfig LoadExplorationConfig(const std::filesystem::path& path) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  const Section s(yaml, path.string(), "",
                  {"world", "start", "seed", "max_time_s", "control_period_s", "timing",
                   "odometry", "laser", "selection", "flops_per_second"});
  ExplorationConfig c;
  std::string world;
  s.Read("world", &world);
  if (world.empty()) s.Fail("world", "a floor-plan file is required");
  c.world = path.parent_path() / world;
  c.start = ReadStart(s);
  s.Read("seed", &c.seed);
  s.Read("max_time_s", &c.run.max_time_s, Bound::kPositive);
  s.Read("control_period_s", &c.run.control_period_s, Bound::kPositive);
  const int timing =
      config::ReadChoice(s, "timing", kTimings, c.run.timing == SlamTiming::kWallClock ? 1 : 0);
  c.run.timing = timing == 1 ? SlamTiming::kWallClock : SlamTiming::kModelledCost;
  const Section odometry = s.Child("odometry", {"sigma_v_mps", "sigma_omega_radps"});
  odometry.Read("sigma_v_mps", &c.run.sigma_v_mps, Bound::kNonNegative);
  odometry.Read("sigma_omega_radps", &c.run.sigma_omega_radps, Bound::kNonNegative);
  ReadLaser(s.Child("laser", {"beams", "range_m", "sigma_range_m"}), &c.run.laser);
  ReadSelection(s.Child("selection", {"policy", "k_max", "min_gain_nats"}), &c.slam);
  s.Read("flops_per_second", &c.slam.flops_per_second, Bound::kPositive);
  c.slam.sigma_v_mps = c.run.sigma_v_mps;
  c.slam.sigma_omega_radps = c.run.sigma_omega_radps;
  c.slam.control_period_s = c.run.control_period_s;
  c.slam.extraction.max_usable_range_m = c.run.laser.range_limit_m;
  c.slam.extraction.sigma_range_m = std::max(c.run.laser.sigma_range_m, 1e-4);
  return c;
}

nlohmann::json ExplorationConfigJson(const ExplorationConfig& c) {
  const bool wall = c.run.timing == SlamTiming::kWallClock;
  return {{"world", c.world.string()},
          {"start", {c.start.x(), c.start.y(), c.start.theta()}},
          {"seed", c.seed},
          {"max_time_s", c.run.max_time_s},
          {"control_period_s", c.run.control_period_s},
          {"timing", wall ? "wall" : "modelled"},
          {"odometry", {{"sigma_v_mps", c.run.sigma_v_mps},
                        {"sigma_omega_radps", c.run.sigma_omega_radps}}},
          {"laser", {{"beams", c.run.laser.beams}, {"range_m", c.run.laser.range_limit_m},
                     {"sigma_range_m", c.run.laser.sigma_range_m}}},
          {"selection", {{"policy", SelectionKindName(c.slam.selection)},
                         {"k_max", c.slam.covariance.k_max},
                         {"min_gain_nats", c.slam.entropy.min_gain_nats}}},
          {"flops_per_second", c.slam.flops_per_second}};
}

}  // namespace slamkit
