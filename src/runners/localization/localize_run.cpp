#include "slamkit/runners/localization/localize_run.hpp"

#include <chrono>
#include <cmath>
#include <utility>

#include "slamkit/io/config_section.hpp"
#include "slamkit/runners/common/log_scoring.hpp"

namespace slamkit {

MclParams LocalizerMclParams() {
  MclParams params;
  params.alpha_slow = 0.001;
  params.alpha_fast = 0.1;
  return params;
}

config::ParamTable LocalizationParamTable(LocalizationConfig& config) {
  using config::Bound;
  using config::Integer;
  using config::Number;
  using config::WithFlag;
  MclParams& m = config.mcl;
  LikelihoodFieldParams& f = config.field;
  MapScanRefinerParams& r = config.refine;
  constexpr Bound kPos = Bound::kPositive, kNonNeg = Bound::kNonNegative;
  return {
      WithFlag(Integer("", "min_particles", &m.min_particles, 1, "fewest particles"),
               "--min-particles"),
      WithFlag(Integer("", "max_particles", &m.max_particles, 1, "most particles"),
               "--max-particles"),
      Number("kld", "error", &m.kld_error, kPos, "", "KLD-sampling's bound on the error"),
      Number("kld", "quantile", &m.kld_quantile, kPos, "", "KLD-sampling's z quantile"),
      Number("kld", "bin_xy_m", &m.bin_xy_m, kPos, "m", "KLD-sampling's bin side"),
      config::Degrees("kld", "bin_theta", &m.bin_theta_rad, kPos, "deg",
                      "KLD-sampling's bin heading width"),
      Number("motion", "srr", &m.motion.srr, kNonNeg, "m/m", "odometry noise: m per m driven"),
      Number("motion", "srt", &m.motion.srt, kNonNeg, "m/rad", "m per rad turned"),
      Number("motion", "str", &m.motion.str, kNonNeg, "rad/m", "rad per m driven"),
      Number("motion", "stt", &m.motion.stt, kNonNeg, "rad/rad", "rad per rad turned"),
      Number("", "update_min_d_m", &m.update_min_d_m, kNonNeg, "m",
             "update after driving this far"),
      Number("", "update_min_a_rad", &m.update_min_a_rad, kNonNeg, "rad",
             "or after turning this far"),
      WithFlag(Integer("laser", "max_beams", &m.max_beams, 1, "beams used per update"),
               "--max-beams"),
      Number("laser", "independent_beams", &m.independent_beams, kPos, "",
             "a weight is the mean per-beam likelihood to this power"),
      Number("laser", "sigma_hit_m", &m.sigma_hit_m, kPos, "m", "the likelihood field's sigma"),
      Number("laser", "z_hit", &m.z_hit, kNonNeg, "", "weight of the likelihood field"),
      Number("laser", "z_rand", &m.z_rand, kPos, "", "weight of a random reading"),
      Number("laser", "usable_range_m", &m.usable_range_m, kPos, "m", "longer readings unused"),
      Number("laser", "max_distance_m", &f.max_distance_m, kPos, "m",
             "distances to the nearest obstacle capped here"),
      Number("recovery", "alpha_slow", &m.alpha_slow, kNonNeg, "",
             "augmented MCL's long-term average rate (0: no random particles)"),
      Number("recovery", "alpha_fast", &m.alpha_fast, kNonNeg, "",
             "augmented MCL's short-term average rate"),
      Integer("recovery", "after_unmatched_scans", &config.recovery_after_unmatched_scans, 0,
              "random particles only after this many scans in a row the map does not match"),
      Number("initial", "sigma_xy_m", &m.initial_sigma_xy_m, kNonNeg, "m",
             "spread around --initial-pose"),
      Number("initial", "sigma_theta_rad", &m.initial_sigma_theta_rad, kNonNeg, "rad",
             "heading spread around --initial-pose"),
      Number("", "cluster_radius_m", &m.cluster_radius_m, kPos, "m",
             "the estimate: mean of the particles this near the heaviest bin"),
      Number("", "converged_spread_m", &m.converged_spread_m, kPos, "m",
             "converged: the particles' position spread below this"),
      Number("map", "occupied_threshold", &f.occupied_threshold, kNonNeg, "",
             "a pixel is occupied above this probability"),
      Number("map", "free_threshold", &f.free_threshold, kNonNeg, "",
             "and free below this"),
      config::Flag("refine", "enabled", &r.enabled,
                   "sharpen each pose by matching the scan against the map"),
      Number("refine", "max_correction_m", &r.max_correction_m, kNonNeg, "m",
             "a match further than this from the estimate is not taken"),
      Number("refine", "max_correction_rad", &r.max_correction_rad, kNonNeg, "rad",
             "nor one turned further than this"),
      Number("refine", "follow_gate_m", &r.follow_gate_m, kNonNeg, "m",
             "match from the last refined pose while it is this near the filter's estimate"),
      Number("refine", "far_step_m", &r.far_step_m, kNonNeg, "m",
             "a scan this far from the one before is matched as the grid filter's particles are"),
      Number("refine", "far_step_rad", &r.far_step_rad, kNonNeg, "rad", "or turned this far"),
      Number("refine", "far_max_correction_m", &r.far_max_correction_m, kNonNeg, "m",
             "such a match further than this from the estimate is not taken"),
      Number("refine", "far_max_correction_rad", &r.far_max_correction_rad, kNonNeg, "rad",
             "nor one turned further than this"),
      WithFlag(config::Seed("", "seed", &m.seed, "random seed of the filter"), "--seed"),
  };
}

LocalizationConfig LoadLocalizationConfig(const std::filesystem::path& path,
                                          const LocalizationConfig& defaults) {
  LocalizationConfig config = defaults;
  config::ReadParams(config::LoadYamlFile(path), path.string(), LocalizationParamTable(config));
  return config;
}

namespace {

// After an update at scan i: the particle counts and whether the filter is settled (converged and
// drawing no random particles, which it does only while it finds the scans unlikely).
void RecordUpdate(const MonteCarloLocalization& mcl, int i, double* particle_sum,
                  LocalizationResult* result) {
  const MclStatus& status = mcl.status();
  *particle_sum += status.particles;
  result->most_particles = std::max(result->most_particles, status.particles);
  if (status.random_fraction > 0.0) {
    ++result->recovery_updates;
    result->last_recovery_scan = i;
  }
  if (!mcl.Converged() || status.random_fraction > 0.0) {
    result->settled_scan.reset();
    return;
  }
  if (!result->settled_scan) result->settled_scan = i;
  if (!result->first_converged_scan) result->first_converged_scan = i;
}

}  // namespace

LocalizationResult RunLocalization(const CarmenLog& log, const OccupancyImage& map,
                                   const LocalizationConfig& config,
                                   const std::optional<Pose2>& initial_pose,
                                   const std::function<void(int, int)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  MonteCarloLocalization mcl(std::make_shared<const LikelihoodField>(map, config.field),
                             config.mcl);
  OccupancyGridParams grid;
  grid.resolution_m = map.resolution_m;
  const MapScanRefiner refiner(OccupancyGridFromImage(map, config.field, grid), config.refine);
  if (initial_pose) {
    mcl.InitialiseAt(*initial_pose);
  } else {
    mcl.InitialiseGlobally();
  }
  LocalizationResult result;
  const int n = static_cast<int>(log.scans.size());
  double particle_sum = 0.0;
  int unmatched = 0;  // scans in a row whose pose the refiner could not match to the map
  for (int i = 0; i < n; ++i) {
    mcl.AllowRecovery(unmatched >= config.recovery_after_unmatched_scans);
    if (mcl.ProcessScan(log.scans[i])) RecordUpdate(mcl, i, &particle_sum, &result);
    Pose2 pose = mcl.CurrentPose();
    bool refined = false;
    if (mcl.Converged()) {
      const Pose2 step = i > 0 ? log.scans[i - 1].odometry.Between(log.scans[i].odometry) : Pose2();
      std::optional<Pose2> followed;
      if (i > 0 && unmatched == 0) followed = result.trajectory.back().pose.Compose(step);
      pose = refiner.Refine(log.scans[i], pose, followed, step, &refined);
    }
    result.refined_scans += refined;
    unmatched = refined ? 0 : unmatched + 1;
    result.trajectory.push_back({log.scans[i].t_s, pose});
    if (progress && (i % 200 == 0 || i + 1 == n)) progress(i + 1, n);
  }
  result.scans = n;
  result.updates = mcl.updates();
  result.mean_particles = result.updates > 0 ? particle_sum / result.updates : 0.0;
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

nlohmann::json LocalizationMetrics(const LocalizationResult& result,
                                   const LocalizationConfig& config,
                                   const RelationErrorStats* relations,
                                   const ReferenceComparison* reference) {
  nlohmann::json m;
  m["scans"] = result.scans;
  m["updates"] = result.updates;
  m["mean_particles"] = result.mean_particles;
  m["most_particles"] = result.most_particles;
  m["refined_scans"] = result.refined_scans;
  m["wall_time_s"] = result.wall_time_s;
  m["scans_per_s"] = result.wall_time_s > 0.0 ? result.scans / result.wall_time_s : 0.0;
  m["converged"] = result.settled_scan.has_value();
  if (result.settled_scan) {
    m["settled_scan"] = *result.settled_scan;
    m["settled_t_s"] = result.trajectory[*result.settled_scan].t_s;
  }
  if (result.first_converged_scan) m["first_converged_scan"] = *result.first_converged_scan;
  m["recovery_updates"] = result.recovery_updates;
  if (result.last_recovery_scan) m["last_recovery_scan"] = *result.last_recovery_scan;
  AddErrorMetrics(relations, reference, m);
  LocalizationConfig copy = config;
  m["params"] = config::ParamsJson(LocalizationParamTable(copy));
  m["peak_rss_mib"] = PeakRssMib();
  return m;
}

}  // namespace slamkit
