#include "slamkit/runners/features/feature_log_config.hpp"

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace slamkit {
namespace {

using config::Bound;
using config::Number;
using config::ParamTable;

constexpr Bound kLogNonNeg = Bound::kNonNegative;
constexpr Bound kLogPos = Bound::kPositive;

void AddLogTop(FeatureLogParams& p, ParamTable& t) {
  const ParamTable lines = {
      config::Choice("selection", "policy", &p.selection,
                     {"all", "entropy", "entropy-fast", "covariance"},
                     "which sightings an update applies"),
      config::Integer("selection", "k_max", &p.covariance.k_max, 0,
                      "covariance policy: most sightings an update applies"),
      Number("selection", "min_gain_nats", &p.entropy.min_gain_nats, kLogNonNeg, "nats",
             "entropy policies: least information gain applied"),
      Number("odometry", "srr", &p.odometry_noise.srr, kLogNonNeg, "m/m", "m per m driven"),
      Number("odometry", "srt", &p.odometry_noise.srt, kLogNonNeg, "m/rad", "m per rad turned"),
      Number("odometry", "str", &p.odometry_noise.str, kLogNonNeg, "rad/m", "rad per m driven"),
      Number("odometry", "stt", &p.odometry_noise.stt, kLogNonNeg, "rad/rad", "rad per rad turned"),
      Number("odometry", "min_sigma_xy_m", &p.min_sigma_xy_m, kLogPos, "m",
             "least translation sigma of a step"),
      Number("odometry", "min_sigma_theta_rad", &p.min_sigma_theta_rad, kLogPos, "rad",
             "least heading sigma of a step"),
      Number("", "linear_update_m", &p.linear_update_m, kLogNonNeg, "m",
             "update after driving this far"),
      Number("", "angular_update_rad", &p.angular_update_rad, kLogNonNeg, "rad",
             "update after turning this far"),
      // The names follow EkfUpdateMode's order.
      config::Choice("", "update", &p.ekf.update, {"dense", "compressed"},
                     "compressed: updates touch the active area only (Guivant & Nebot 2001)"),
      Number("", "area_hysteresis", &p.ekf.active_area.hysteresis_fraction, kLogPos, "",
             "compressed: a new area when the robot is this fraction of its reach away"),
      Number("", "area_sigma_factor", &p.ekf.active_area.sigma_factor, kLogNonNeg, "",
             "compressed: the area widened by this many position sigmas"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddLogExtraction(LineExtractionParams& e, ParamTable& t) {
  const std::string s = "extraction";
  const ParamTable lines = {
      config::Limit(s, "max_usable_range_m", &e.max_usable_range_m, "m",
                    "beams beyond this are not used (null: all)", kLogPos),
      Number(s, "max_gap_m", &e.max_gap_m, kLogPos, "m", "a gap this wide splits a segment"),
      Number(s, "split_distance_m", &e.split_distance_m, kLogPos, "m",
             "split where a point is this far from the chord"),
      Number(s, "merge_max_angle_rad", &e.merge_max_angle_rad, kLogNonNeg, "rad",
             "merge neighbours within this angle"),
      Number(s, "merge_max_mahalanobis2", &e.merge_max_mahalanobis2, kLogNonNeg, "",
             "... and this squared Mahalanobis distance"),
      config::Integer(s, "min_points", &e.min_points, 2, "fewest points of a line"),
      Number(s, "min_length_m", &e.min_length_m, kLogNonNeg, "m", "shortest line"),
      Number(s, "max_residual_rms_m", &e.max_residual_rms_m, kLogPos, "m",
             "largest RMS residual of a line's points"),
      Number(s, "sigma_range_m", &e.sigma_range_m, kLogPos, "m", "a beam's range sigma"),
      Number(s, "sigma_bearing_rad", &e.sigma_bearing_rad, kLogPos, "rad",
             "a beam's bearing sigma"),
      Number(s, "wall_sigma_rho_m", &e.wall_sigma_rho_m, kLogNonNeg, "m",
             "a wall's roughness in distance"),
      Number(s, "wall_sigma_alpha_rad", &e.wall_sigma_alpha_rad, kLogNonNeg, "rad",
             "... and in direction"),
      Number(s, "min_corner_angle_rad", &e.min_corner_angle_rad, kLogNonNeg, "rad",
             "a corner's smallest angle between its lines"),
      Number(s, "max_corner_angle_rad", &e.max_corner_angle_rad, kLogNonNeg, "rad",
             "... and largest"),
      Number(s, "max_corner_endpoint_distance_m", &e.max_corner_endpoint_distance_m, kLogNonNeg,
             "m", "a corner's lines end within this of it"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddLogLandmarks(FeatureLogParams& p, ParamTable& t) {
  LineAssociationParams& l = p.ekf.lines;
  const ParamTable lines = {
      Number("lines", "gate_chi2", &l.gate_chi2, kLogPos, "", "a line's association gate"),
      Number("lines", "new_landmark_chi2", &l.new_landmark_chi2, kLogPos, "",
             "a line this far from every one is new"),
      Number("lines", "overlap_margin_m", &l.overlap_margin_m, kLogNonNeg, "m",
             "a line matches a landmark it overlaps within this"),
      Number("lines", "min_new_length_m", &l.min_new_length_m, kLogNonNeg, "m",
             "shortest line made a landmark"),
      Number("lines", "new_min_separation_rho_m", &l.new_min_separation_rho_m, kLogNonNeg, "m",
             "a new line at least this far from the others in distance"),
      Number("lines", "new_min_separation_alpha_rad", &l.new_min_separation_alpha_rad, kLogNonNeg,
             "rad", "... or in direction"),
      Number("lines", "min_rho_m", &p.ekf.min_line_rho_m, kLogNonNeg, "m",
             "lines through the robot closer than this are not used"),
      Number("corners", "gate_chi2", &p.ekf.corners.gate_chi2, kLogPos, "",
             "a corner's association gate"),
      Number("corners", "new_landmark_chi2", &p.ekf.corners.new_landmark_chi2, kLogPos, "",
             "a corner this far from every one is new"),
      Number("corners", "reach_m", &p.ekf.corner_reach_m, kLogPos, "m", "corners within this"),
      config::Integer("", "accuracy_ratio_every", &p.accuracy_ratio_every, 0,
                      "score against the full EKF every this many updates (0: never)"),
      config::Limit("", "max_wall_time_s", &p.max_wall_time_s, "s",
                    "stop after this much wall time (null: never)", kLogPos),
      Number("", "flops_per_second", &p.flops_per_second, kLogPos, "1/s",
             "the modelled machine's speed"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

}  // namespace

config::ParamTable FeatureLogParamTable(FeatureLogParams& params) {
  ParamTable t;
  AddLogTop(params, t);
  AddLogExtraction(params.extraction, t);
  AddLogLandmarks(params, t);
  return t;
}

FeatureLogParams LoadFeatureLogConfig(const std::filesystem::path& path,
                                      const FeatureLogParams& defaults) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  FeatureLogParams p = defaults;
  config::ReadParams(yaml, path.string(), FeatureLogParamTable(p));
  return p;
}

nlohmann::json FeatureLogParamsJson(const FeatureLogParams& params) {
  FeatureLogParams p = params;
  return config::ParamsJson(FeatureLogParamTable(p));
}

}  // namespace slamkit
