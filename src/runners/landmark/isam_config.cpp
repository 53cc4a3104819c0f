#include "slamkit/runners/landmark/isam_config.hpp"

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "slamkit/io/config_section.hpp"
#include "slamkit/runners/landmark/fastslam_sampling.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Number;
using config::ParamTable;
using config::Section;

void AddIsamAssociation(EkfSlamParams& e, IsamFastSlamSettings& f, ParamTable& t) {
  const ParamTable lines = {
      // In AssociationMethod's order.
      config::Choice("", "association", &e.association_method, {"nn", "known", "jcbb", "ml", "gnn"},
                     "the EKF's data association"),
      Number("", "gate_chi2", &e.association.gate_chi2, Bound::kPositive, "",
             "a sighting matches a landmark within this chi-square"),
      Number("", "new_landmark_chi2", &e.association.new_landmark_chi2, Bound::kPositive, "",
             "a sighting beyond this from every landmark is a new one"),
      config::Integer("", "max_joint_tests", &e.jcbb.max_joint_tests, 1,
                      "JCBB: most joint-compatibility tests a scan may take"),
      // In EkfUpdateMode's order.
      config::Choice("", "update", &e.update, {"dense", "compressed"},
                     "compressed: the EKF's updates touch the active area only"),
      config::Choice("fastslam", "new_landmark_test", &f.new_landmark_test,
                     {"likelihood", "mahalanobis"}, "FastSLAM: what makes a sighting new"),
      config::Optional("fastslam", "gate_chi2", &f.gate_chi2, Bound::kPositive, "",
                       "FastSLAM's gate (unset: the EKF's)"),
      config::Optional("fastslam", "new_landmark_chi2", &f.new_landmark_chi2, Bound::kPositive, "",
                       "FastSLAM's new-landmark gate (unset: the EKF's)"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
  AddDelayedSamplingLines("fastslam", &f.delayed_sampling, &f.window_max_landmarks, &t);
}

void AddIsamNoise(IsamRunParams& p, ParamTable& t) {
  constexpr Bound kNonNeg = Bound::kNonNegative;
  const ParamTable lines = {
      Number("odometry", "covariance_scale", &p.odometry_covariance_scale, Bound::kPositive, "",
             "multiplies the file's odometry covariances"),
      Number("odometry", "srr", &p.odometry_noise.srr, kNonNeg, "m/m", "added: m per m driven"),
      Number("odometry", "srt", &p.odometry_noise.srt, kNonNeg, "m/rad", "m per rad turned"),
      Number("odometry", "str", &p.odometry_noise.str, kNonNeg, "rad/m", "rad per m driven"),
      Number("odometry", "stt", &p.odometry_noise.stt, kNonNeg, "rad/rad", "rad per rad turned"),
      Number("odometry", "heading_drift_rad_per_m", &p.odometry_heading_drift_rad_per_m,
             Bound::kFinite, "rad/m", "odometry calibration: extra turn per metre driven"),
      Number("sightings", "covariance_scale", &p.sighting_covariance_scale, Bound::kPositive, "",
             "multiplies the file's sighting covariances"),
      Number("sightings", "sigma_range_m", &p.sighting_sigma_range_m, kNonNeg, "m",
             "replaces the file's range sigma (0: kept)"),
      config::Degrees("sightings", "sigma_bearing_deg", &p.sighting_sigma_bearing_rad, kNonNeg,
                      "deg", "replaces the file's bearing sigma (0: kept)"),
      config::Flag("", "score_against_merged_reference", &p.score_against_merged_reference,
                   "score against the reference with its duplicate landmarks merged"),
      config::Flag("", "compare_with_smoothed_reference", &p.compare_with_smoothed_reference,
                   "compare with the smoothed reference"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

// The checks between keys, once every key is read.
void CheckIsamParams(const YAML::Node& yaml, const std::string& file, const ParamTable& table,
                     const IsamRunParams& p) {
  const Section s = config::TableSection(yaml, file, table, "");
  const EkfSlamParams& e = p.ekf;
  if (e.association.new_landmark_chi2 < e.association.gate_chi2) {
    s.Fail(s.Has("new_landmark_chi2") ? "new_landmark_chi2" : "gate_chi2",
           "new_landmark_chi2 must be >= gate_chi2");
  }
  const IsamFastSlamSettings& f = p.fastslam;
  if (f.gate_chi2 && f.new_landmark_chi2 && *f.new_landmark_chi2 < *f.gate_chi2) {
    config::TableSection(yaml, file, table, "fastslam")
        .Fail("new_landmark_chi2", "new_landmark_chi2 must be >= gate_chi2");
  }
  if ((p.sighting_sigma_range_m > 0.0) != (p.sighting_sigma_bearing_rad > 0.0)) {
    const Section z = config::TableSection(yaml, file, table, "sightings");
    z.Fail(z.Has("sigma_range_m") ? "sigma_range_m" : "sigma_bearing_deg",
           "sigma_range_m and sigma_bearing_deg are both positive (the file's covariance is "
           "replaced) or both 0 (it is kept)");
  }
}

}  // namespace

config::ParamTable IsamParamTable(IsamRunParams& params) {
  ParamTable t;
  AddIsamAssociation(params.ekf, params.fastslam, t);
  AddIsamNoise(params, t);
  return t;
}

IsamRunParams LoadIsamConfig(const std::filesystem::path& path, const IsamRunParams& defaults) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  IsamRunParams p = defaults;
  const ParamTable table = IsamParamTable(p);
  config::ReadParams(yaml, path.string(), table);
  CheckIsamParams(yaml, path.string(), table, p);
  return p;
}

nlohmann::json IsamParamsJson(const IsamRunParams& params) {
  IsamRunParams p = params;
  return config::ParamsJson(IsamParamTable(p));
}

}  // namespace slamkit
