#include "slamkit/runners/grid/grid_config.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "slamkit/io/config_section.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Section;

const std::vector<std::string> kProposals = {"gaussian", "scan_match"};
const std::vector<std::string> kTracking = {"tracked_motion", "track_only", "off"};
const std::vector<std::string> kResampling = {"systematic", "stratified", "multinomial"};

int ProposalIndex(ProposalScheme p) { return p == ProposalScheme::kGaussian ? 0 : 1; }
ProposalScheme ProposalOf(int i) {
  return i == 0 ? ProposalScheme::kGaussian : ProposalScheme::kScanMatch;
}
int TrackingIndex(TrackingMode m) {
  return m == TrackingMode::kTrackedMotion ? 0 : m == TrackingMode::kTrackOnly ? 1 : 2;
}
TrackingMode TrackingOf(int i) {
  return i == 0 ? TrackingMode::kTrackedMotion
                : i == 1 ? TrackingMode::kTrackOnly : TrackingMode::kOff;
}
int ResamplingIndex(ResamplingScheme s) {
  return s == ResamplingScheme::kSystematic ? 0 : s == ResamplingScheme::kStratified ? 1 : 2;
}
ResamplingScheme ResamplingOf(int i) {
  return i == 0 ? ResamplingScheme::kSystematic
                : i == 1 ? ResamplingScheme::kStratified : ResamplingScheme::kMultinomial;
}

void ReadMatcher(const Section& s, ScanMatcherParams* m) {
  s.Read("beam_stride", &m->beam_stride, 1);
  s.Read("search_cells", &m->search_cells, 0);
  s.Read("score_sigma_m", &m->score_sigma_m, Bound::kPositive);
  s.Read("likelihood_sigma_m", &m->likelihood_sigma_m, Bound::kPositive);
  s.Read("linear_step_m", &m->linear_step_m, Bound::kPositive);
  s.Read("angular_step_rad", &m->angular_step_rad, Bound::kPositive);
  s.Read("refinements", &m->refinements, 0);
  s.Read("min_score_fraction", &m->min_score_fraction, Bound::kNonNegative);
  s.Read("prior_sigma_xy_m", &m->prior_sigma_xy_m, Bound::kNonNegative);
  s.Read("prior_sigma_theta_rad", &m->prior_sigma_theta_rad, Bound::kNonNegative);
  s.Read("coarse_pass", &m->coarse_pass);
  s.Read("coarse_search_cells", &m->coarse_search_cells, 0);
  s.Read("coarse_score_sigma_m", &m->coarse_score_sigma_m, Bound::kPositive);
  s.Read("coarse_beam_stride", &m->coarse_beam_stride, 1);
  s.Read("coarse_refinements", &m->coarse_refinements, 0);
  s.Read("heading_sweep_rad", &m->heading_sweep_rad, Bound::kNonNegative);
  s.Read("heading_sweep_step_rad", &m->heading_sweep_step_rad, Bound::kPositive);
  s.Read("widen_below_score_fraction", &m->widen_below_score_fraction, Bound::kNonNegative);
  s.Read("widen_heading_step_rad", &m->widen_heading_step_rad, Bound::kPositive);
  s.Read("widen_heading_starts", &m->widen_heading_starts, 0);
  MatchConstraintParams& c = m->constraints;
  s.Read("min_information_ratio", &c.min_information_ratio, Bound::kNonNegative);
  s.Read("normal_neighbours", &c.normal_neighbours, 1);
  s.Read("normal_radius_m", &c.normal_radius_m, Bound::kPositive);
  s.Read("max_normal_spread", &c.max_normal_spread, Bound::kNonNegative);
}

// A limit that may be infinite (none): null in YAML, as metrics.json writes it (JSON has no
// infinity).
void ReadOptionalLimit(const Section& s, const std::string& key, double* value) {
  if (s.Has(key) && s.Get(key).IsNull()) {
    *value = std::numeric_limits<double>::infinity();
  } else {
    s.Read(key, value, Bound::kNonNegative);
  }
}

nlohmann::json LimitJson(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

const std::vector<std::string> kMatcherKeys = {
    "beam_stride", "search_cells", "score_sigma_m", "likelihood_sigma_m", "linear_step_m",
    "angular_step_rad", "refinements", "min_score_fraction", "prior_sigma_xy_m",
    "prior_sigma_theta_rad", "coarse_pass", "coarse_search_cells", "coarse_score_sigma_m",
    "coarse_beam_stride", "coarse_refinements", "heading_sweep_rad", "heading_sweep_step_rad",
    "widen_below_score_fraction",
    "widen_heading_step_rad", "widen_heading_starts", "min_information_ratio", "normal_neighbours",
    "normal_radius_m", "max_normal_spread"};

nlohmann::json MatcherJson(const ScanMatcherParams& m) {
  return {{"beam_stride", m.beam_stride}, {"search_cells", m.search_cells},
          {"score_sigma_m", m.score_sigma_m}, {"likelihood_sigma_m", m.likelihood_sigma_m},
          {"linear_step_m", m.linear_step_m}, {"angular_step_rad", m.angular_step_rad},
          {"refinements", m.refinements}, {"min_score_fraction", m.min_score_fraction},
          {"prior_sigma_xy_m", m.prior_sigma_xy_m},
          {"prior_sigma_theta_rad", m.prior_sigma_theta_rad}, {"coarse_pass", m.coarse_pass},
          {"coarse_search_cells", m.coarse_search_cells},
          {"coarse_score_sigma_m", m.coarse_score_sigma_m},
          {"coarse_beam_stride", m.coarse_beam_stride},
          {"coarse_refinements", m.coarse_refinements},
          {"heading_sweep_rad", m.heading_sweep_rad},
          {"heading_sweep_step_rad", m.heading_sweep_step_rad},
          {"widen_below_score_fraction", m.widen_below_score_fraction},
          {"widen_heading_step_rad", m.widen_heading_step_rad},
          {"widen_heading_starts", m.widen_heading_starts},
          {"min_information_ratio", m.constraints.min_information_ratio},
          {"normal_neighbours", m.constraints.normal_neighbours},
          {"normal_radius_m", m.constraints.normal_radius_m},
          {"max_normal_spread", m.constraints.max_normal_spread}};
}

void ReadGrid(const Section& s, OccupancyGridParams* g) {
  s.Read("resolution_m", &g->resolution_m, Bound::kPositive);
  double value = 0.0;
  for (auto [key, field] : {std::pair{"log_odds_hit", &g->log_odds_hit},
                            std::pair{"log_odds_miss", &g->log_odds_miss},
                            std::pair{"log_odds_min", &g->log_odds_min},
                            std::pair{"log_odds_max", &g->log_odds_max}}) {
    value = *field;
    s.Read(key, &value);
    *field = static_cast<float>(value);
  }
  s.Read("max_extent_m", &g->max_extent_m, Bound::kPositive);
  s.Read("max_cells", &g->max_cells);
  if (g->log_odds_min >= g->log_odds_max) s.Fail("log_odds_min", "must be below log_odds_max");
}

}  // namespace

GridSlamConfig LoadGridConfig(const std::filesystem::path& path,
                              const GridSlamConfig& defaults) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  const Section s(yaml, path.string(), "",
                  {"backend", "particles", "seed", "linear_update_m", "angular_update_rad", "resampling",
                   "likelihood_gain", "motion", "usable_range_m", "misses_spare_scan_hits",
                   "no_return_ray_length_m", "matcher",
                   "widen_below_typical_score", "proposal", "sampled_start_fraction",
                   "heading_sweep_sigmas", "gaussian", "tracking_mode", "tracking",
                   "tracking_max_correction_m", "tracking_max_correction_rad",
                   "tracking_max_step_m", "tracking_max_step_rad", "grid"});
  GridSlamConfig config = defaults;
  config.backend = static_cast<GridBackend>(config::ReadChoice(
      s, "backend", GridBackendNames(), static_cast<int>(defaults.backend)));
  RbpfGridSlamParams& p = config.rbpf;
  s.Read("particles", &p.particles, 1);
  s.Read("seed", &p.seed);
  s.Read("linear_update_m", &p.linear_update_m, Bound::kNonNegative);
  s.Read("angular_update_rad", &p.angular_update_rad, Bound::kNonNegative);
  const Section r = s.Child("resampling", {"threshold", "scheme"});
  r.Read("threshold", &p.resampling.threshold, Bound::kNonNegative);
  p.resampling.scheme = ResamplingOf(
      config::ReadChoice(r, "scheme", kResampling, ResamplingIndex(p.resampling.scheme)));
  s.Read("likelihood_gain", &p.likelihood_gain, Bound::kPositive);
  const Section m = s.Child("motion", {"srr", "srt", "str", "stt", "heading_drift_rad_per_m",
                                       "estimate_heading_drift", "heading_drift_prior_m2"});
  m.Read("srr", &p.motion.srr, Bound::kNonNegative);
  m.Read("srt", &p.motion.srt, Bound::kNonNegative);
  m.Read("str", &p.motion.str, Bound::kNonNegative);
  m.Read("stt", &p.motion.stt, Bound::kNonNegative);
  m.Read("heading_drift_rad_per_m", &p.odometry_heading_drift_rad_per_m, Bound::kFinite);
  m.Read("estimate_heading_drift", &p.estimate_heading_drift);
  m.Read("heading_drift_prior_m2", &p.heading_drift_prior_m2, Bound::kPositive);
  s.Read("usable_range_m", &p.usable_range_m, Bound::kPositive);
  s.Read("misses_spare_scan_hits", &p.misses_spare_scan_hits);
  ReadOptionalLimit(s, "no_return_ray_length_m", &p.no_return_ray_length_m);
  ReadMatcher(s.Child("matcher", kMatcherKeys), &p.matcher);
  s.Read("widen_below_typical_score", &p.widen_below_typical_score, Bound::kNonNegative);
  p.proposal = ProposalOf(config::ReadChoice(s, "proposal", kProposals, ProposalIndex(p.proposal)));
  s.Read("sampled_start_fraction", &p.sampled_start_fraction, Bound::kNonNegative);
  if (p.sampled_start_fraction > 1.0) s.Fail("sampled_start_fraction", "must be at most 1");
  s.Read("heading_sweep_sigmas", &p.heading_sweep_sigmas, Bound::kNonNegative);
  const Section g = s.Child("gaussian", {"step_xy_m", "step_theta_rad"});
  g.Read("step_xy_m", &p.gaussian.step_xy_m, Bound::kPositive);
  g.Read("step_theta_rad", &p.gaussian.step_theta_rad, Bound::kPositive);
  p.tracking_mode = TrackingOf(
      config::ReadChoice(s, "tracking_mode", kTracking, TrackingIndex(p.tracking_mode)));
  ReadMatcher(s.Child("tracking", kMatcherKeys), &p.tracking);
  s.Read("tracking_max_correction_m", &p.tracking_max_correction_m, Bound::kNonNegative);
  s.Read("tracking_max_correction_rad", &p.tracking_max_correction_rad, Bound::kNonNegative);
  ReadOptionalLimit(s, "tracking_max_step_m", &p.tracking_max_step_m);
  ReadOptionalLimit(s, "tracking_max_step_rad", &p.tracking_max_step_rad);
  ReadGrid(s.Child("grid", {"resolution_m", "log_odds_hit", "log_odds_miss", "log_odds_min",
                            "log_odds_max", "max_extent_m", "max_cells"}),
           &p.grid);
  return config;
}

nlohmann::json GridParamsJson(const GridSlamConfig& config) {
  const RbpfGridSlamParams& p = config.rbpf;
  const OccupancyGridParams& g = p.grid;
  return {{"backend", GridBackendNames()[static_cast<int>(config.backend)]},
          {"particles", p.particles},
          {"seed", p.seed},
          {"linear_update_m", p.linear_update_m},
          {"angular_update_rad", p.angular_update_rad},
          {"resampling", {{"threshold", p.resampling.threshold},
                          {"scheme", kResampling[ResamplingIndex(p.resampling.scheme)]}}},
          {"likelihood_gain", p.likelihood_gain},
          {"motion", {{"srr", p.motion.srr}, {"srt", p.motion.srt}, {"str", p.motion.str},
                      {"stt", p.motion.stt},
                      {"heading_drift_rad_per_m", p.odometry_heading_drift_rad_per_m},
                      {"estimate_heading_drift", p.estimate_heading_drift},
                      {"heading_drift_prior_m2", p.heading_drift_prior_m2}}},
          {"usable_range_m", p.usable_range_m},
          {"misses_spare_scan_hits", p.misses_spare_scan_hits},
          {"no_return_ray_length_m", LimitJson(p.no_return_ray_length_m)},
          {"matcher", MatcherJson(p.matcher)},
          {"widen_below_typical_score", p.widen_below_typical_score},
          {"proposal", kProposals[ProposalIndex(p.proposal)]},
          {"sampled_start_fraction", p.sampled_start_fraction},
          {"heading_sweep_sigmas", p.heading_sweep_sigmas},
          {"gaussian", {{"step_xy_m", p.gaussian.step_xy_m},
                        {"step_theta_rad", p.gaussian.step_theta_rad}}},
          {"tracking_mode", kTracking[TrackingIndex(p.tracking_mode)]},
          {"tracking", MatcherJson(p.tracking)},
          {"tracking_max_correction_m", p.tracking_max_correction_m},
          {"tracking_max_correction_rad", p.tracking_max_correction_rad},
          {"tracking_max_step_m", LimitJson(p.tracking_max_step_m)},
          {"tracking_max_step_rad", LimitJson(p.tracking_max_step_rad)},
          {"grid", {{"resolution_m", g.resolution_m}, {"log_odds_hit", g.log_odds_hit},
                    {"log_odds_miss", g.log_odds_miss}, {"log_odds_min", g.log_odds_min},
                    {"log_odds_max", g.log_odds_max}, {"max_extent_m", g.max_extent_m},
                    {"max_cells", g.max_cells}}}};
}

}  // namespace slamkit
