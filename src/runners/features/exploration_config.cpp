#include "slamkit/runners/features/exploration_config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <string>
#include <vector>

#include "slamkit/io/config_section.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Describe;
using config::Section;

Pose2 ReadStart(const Section& s) {
  if (!s.Has("start")) return Pose2();
  const YAML::Node v = s.Get("start");
  if (!v.IsSequence() || v.size() != 3) {
    s.Fail("start", "expected [x_m, y_m, theta_rad], got " + Describe(v));
  }
  return Pose2(s.Number("start", v[0], Bound::kFinite), s.Number("start", v[1], Bound::kFinite),
               s.Number("start", v[2], Bound::kFinite));
}

// The file names the choices in this order, SlamTiming has them the other way round.
config::Param TimingLine(SlamTiming* timing) {
  config::ChoiceRef choice{
      {"modelled", "wall"},
      [timing] { return *timing == SlamTiming::kWallClock ? 1 : 0; },
      [timing](int i) { *timing = i == 1 ? SlamTiming::kWallClock : SlamTiming::kModelledCost; }};
  return {"", "timing", "", "SLAM's time: modelled from its cost, or the wall clock", "", choice};
}

}  // namespace

config::ParamTable ExplorationParamTable(ExplorationConfig& c) {
  using config::Number;
  constexpr Bound kNonNeg = Bound::kNonNegative;
  constexpr Bound kPos = Bound::kPositive;
  return {
      config::Listed("", "world", "the floor-plan file, relative to the config's folder"),
      config::Listed("", "start", "the start pose [x_m, y_m, theta_rad]"),
      config::Seed("", "seed", &c.seed, "random seed"),
      Number("", "max_time_s", &c.run.max_time_s, kPos, "s", "the run's length"),
      Number("", "control_period_s", &c.run.control_period_s, kPos, "s", "a control step"),
      TimingLine(&c.run.timing),
      Number("odometry", "sigma_v_mps", &c.run.sigma_v_mps, kNonNeg, "m/s", "speed noise"),
      Number("odometry", "sigma_omega_radps", &c.run.sigma_omega_radps, kNonNeg, "rad/s",
             "turn-rate noise"),
      config::Integer("laser", "beams", &c.run.laser.beams, 2, "beams of a scan"),
      Number("laser", "range_m", &c.run.laser.range_limit_m, kPos, "m", "the laser's range"),
      Number("laser", "sigma_range_m", &c.run.laser.sigma_range_m, kNonNeg, "m", "range noise"),
      config::Choice("selection", "policy", &c.slam.selection,
                     {"all", "entropy", "entropy-fast", "covariance"},
                     "which sightings an update applies"),
      config::Integer("selection", "k_max", &c.slam.covariance.k_max, 1,
                      "covariance policy: most sightings an update applies"),
      Number("selection", "min_gain_nats", &c.slam.entropy.min_gain_nats, kNonNeg, "nats",
             "entropy policies: least information gain applied"),
      Number("", "flops_per_second", &c.slam.flops_per_second, kPos, "1/s",
             "the modelled machine's speed"),
  };
}

ExplorationConfig LoadExplorationConfig(const std::filesystem::path& path) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  ExplorationConfig c;
  const config::ParamTable table = ExplorationParamTable(c);
  const Section s = config::TableSection(yaml, path.string(), table, "");
  std::string world;
  s.Read("world", &world);
  if (world.empty()) s.Fail("world", "a floor-plan file is required");
  c.world = path.parent_path() / world;
  c.start = ReadStart(s);
  config::ReadParams(yaml, path.string(), table);
  // No-return beams read the range, as the seed's.
  c.run.laser.max_range_m = c.run.laser.range_limit_m;
  c.slam.sigma_v_mps = c.run.sigma_v_mps;
  c.slam.sigma_omega_radps = c.run.sigma_omega_radps;
  c.slam.control_period_s = c.run.control_period_s;
  c.slam.extraction.max_usable_range_m = c.run.laser.range_limit_m;
  c.slam.extraction.sigma_range_m = std::max(c.run.laser.sigma_range_m, 1e-4);
  return c;
}

nlohmann::json ExplorationConfigJson(const ExplorationConfig& config) {
  ExplorationConfig c = config;
  nlohmann::json j = config::ParamsJson(ExplorationParamTable(c));
  j["world"] = c.world.string();
  j["start"] = {c.start.x(), c.start.y(), c.start.theta()};
  return j;
}

}  // namespace slamkit
