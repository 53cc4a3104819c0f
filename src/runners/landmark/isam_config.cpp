#include "slamkit/runners/landmark/isam_config.hpp"

#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/config_section.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Section;

// In AssociationMethod's order.
const std::vector<std::string> kAssociations = {"nn", "known", "jcbb", "ml", "gnn"};

void ReadAssociation(const Section& s, EkfSlamParams* ekf) {
  ekf->association_method = static_cast<AssociationMethod>(config::ReadChoice(
      s, "association", kAssociations, static_cast<int>(ekf->association_method)));
  s.Read("gate_chi2", &ekf->association.gate_chi2, Bound::kPositive);
  s.Read("new_landmark_chi2", &ekf->association.new_landmark_chi2, Bound::kPositive);
  if (ekf->association.new_landmark_chi2 < ekf->association.gate_chi2) {
    s.Fail(s.Has("new_landmark_chi2") ? "new_landmark_chi2" : "gate_chi2",
           "new_landmark_chi2 must be >= gate_chi2");
  }
  int max_joint_tests = static_cast<int>(ekf->jcbb.max_joint_tests);
  s.Read("max_joint_tests", &max_joint_tests, 1);
  ekf->jcbb.max_joint_tests = max_joint_tests;
}

const std::vector<std::string> kNewLandmarkTests = {"likelihood", "mahalanobis"};

void ReadFastSlam(const Section& parent, IsamFastSlamSettings* f) {
  const Section s =
      parent.Child("fastslam", {"new_landmark_test", "gate_chi2", "new_landmark_chi2",
                                "delayed_sampling", "window_max_landmarks"});
  f->new_landmark_test = static_cast<NewLandmarkTest>(config::ReadChoice(
      s, "new_landmark_test", kNewLandmarkTests, static_cast<int>(f->new_landmark_test)));
  for (const auto& [key, value] : {std::pair{"gate_chi2", &f->gate_chi2},
                                   std::pair{"new_landmark_chi2", &f->new_landmark_chi2}}) {
    if (!s.Has(key)) continue;
    double v = 0.0;
    s.Read(key, &v, Bound::kPositive);
    *value = v;
  }
  s.Read("delayed_sampling", &f->delayed_sampling);
  s.Read("window_max_landmarks", &f->window_max_landmarks, 1);
  if (f->gate_chi2 && f->new_landmark_chi2 && *f->new_landmark_chi2 < *f->gate_chi2) {
    s.Fail("new_landmark_chi2", "new_landmark_chi2 must be >= gate_chi2");
  }
}

// Unset gates are left out (they follow the EKF's), so that the file reads back as it was.
nlohmann::json FastSlamJson(const IsamFastSlamSettings& f) {
  nlohmann::json j = {
      {"new_landmark_test", kNewLandmarkTests[static_cast<int>(f.new_landmark_test)]},
      {"delayed_sampling", f.delayed_sampling},
      {"window_max_landmarks", f.window_max_landmarks}};
  if (f.gate_chi2) j["gate_chi2"] = *f.gate_chi2;
  if (f.new_landmark_chi2) j["new_landmark_chi2"] = *f.new_landmark_chi2;
  return j;
}

}  // namespace

IsamRunParams LoadIsamConfig(const std::filesystem::path& path, const IsamRunParams& defaults) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  const Section s(yaml, path.string(), "",
                  {"association", "gate_chi2", "new_landmark_chi2", "max_joint_tests", "odometry",
                   "sightings", "score_against_merged_reference",
                   "compare_with_smoothed_reference", "fastslam"});
  IsamRunParams p = defaults;
  ReadAssociation(s, &p.ekf);
  ReadFastSlam(s, &p.fastslam);
  const Section o = s.Child("odometry", {"covariance_scale", "srr", "srt", "str", "stt",
                                         "heading_drift_rad_per_m"});
  o.Read("covariance_scale", &p.odometry_covariance_scale, Bound::kPositive);
  o.Read("srr", &p.odometry_noise.srr, Bound::kNonNegative);
  o.Read("srt", &p.odometry_noise.srt, Bound::kNonNegative);
  o.Read("str", &p.odometry_noise.str, Bound::kNonNegative);
  o.Read("stt", &p.odometry_noise.stt, Bound::kNonNegative);
  o.Read("heading_drift_rad_per_m", &p.odometry_heading_drift_rad_per_m, Bound::kFinite);
  const Section z =
      s.Child("sightings", {"covariance_scale", "sigma_range_m", "sigma_bearing_deg"});
  z.Read("covariance_scale", &p.sighting_covariance_scale, Bound::kPositive);
  z.Read("sigma_range_m", &p.sighting_sigma_range_m, Bound::kNonNegative);
  z.ReadDegrees("sigma_bearing_deg", &p.sighting_sigma_bearing_rad, Bound::kNonNegative);
  if ((p.sighting_sigma_range_m > 0.0) != (p.sighting_sigma_bearing_rad > 0.0)) {
    z.Fail(z.Has("sigma_range_m") ? "sigma_range_m" : "sigma_bearing_deg",
           "sigma_range_m and sigma_bearing_deg are both positive (the file's covariance is "
           "replaced) or both 0 (it is kept)");
  }
  s.Read("score_against_merged_reference", &p.score_against_merged_reference);
  s.Read("compare_with_smoothed_reference", &p.compare_with_smoothed_reference);
  return p;
}

nlohmann::json IsamParamsJson(const IsamRunParams& p) {
  const EkfSlamParams& e = p.ekf;
  return {{"association", kAssociations[static_cast<int>(e.association_method)]},
          {"gate_chi2", e.association.gate_chi2},
          {"new_landmark_chi2", e.association.new_landmark_chi2},
          {"max_joint_tests", e.jcbb.max_joint_tests},
          {"odometry",
           {{"covariance_scale", p.odometry_covariance_scale},
            {"srr", p.odometry_noise.srr},
            {"srt", p.odometry_noise.srt},
            {"str", p.odometry_noise.str},
            {"stt", p.odometry_noise.stt},
            {"heading_drift_rad_per_m", p.odometry_heading_drift_rad_per_m}}},
          {"sightings",
           {{"covariance_scale", p.sighting_covariance_scale},
            {"sigma_range_m", p.sighting_sigma_range_m},
            {"sigma_bearing_deg", RadToDeg(p.sighting_sigma_bearing_rad)}}},
          {"score_against_merged_reference", p.score_against_merged_reference},
          {"compare_with_smoothed_reference", p.compare_with_smoothed_reference},
          {"fastslam", FastSlamJson(p.fastslam)}};
}

}  // namespace slamkit
