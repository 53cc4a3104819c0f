#include "slamkit/runners/features/feature_log_config.hpp"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "slamkit/io/config_section.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Section;

const std::vector<std::string> kPolicies = {"all", "entropy", "entropy-fast", "covariance"};

// One number of the config: where it lives (section "" is the top level) and what it may be.
struct Field {
  const char* section;
  const char* key;
  double* number = nullptr;
  int* integer = nullptr;
  bool* flag = nullptr;
  Bound bound = Bound::kNonNegative;
  int min = 0;
  bool infinity_allowed = false;  // null in the file and in metrics.json
};

Field Number(const char* section, const char* key, double* v, Bound bound = Bound::kNonNegative,
             bool infinity_allowed = false) {
  return {section, key, v, nullptr, nullptr, bound, 0, infinity_allowed};
}

// The one list both the reader and the JSON writer go through, so they cannot disagree.
std::vector<Field> Fields(FeatureLogParams& p) {
  LineExtractionParams& e = p.extraction;
  LineAssociationParams& l = p.ekf.lines;
  return {
      {"selection", "k_max", nullptr, &p.covariance.k_max, nullptr, Bound::kFinite, 0},
      Number("selection", "min_gain_nats", &p.entropy.min_gain_nats),
      Number("odometry", "srr", &p.odometry_noise.srr),
      Number("odometry", "srt", &p.odometry_noise.srt),
      Number("odometry", "str", &p.odometry_noise.str),
      Number("odometry", "stt", &p.odometry_noise.stt),
      Number("odometry", "min_sigma_xy_m", &p.min_sigma_xy_m, Bound::kPositive),
      Number("odometry", "min_sigma_theta_rad", &p.min_sigma_theta_rad, Bound::kPositive),
      Number("", "linear_update_m", &p.linear_update_m),
      Number("", "angular_update_rad", &p.angular_update_rad),
      Number("extraction", "max_usable_range_m", &e.max_usable_range_m, Bound::kPositive, true),
      Number("extraction", "max_gap_m", &e.max_gap_m, Bound::kPositive),
      Number("extraction", "split_distance_m", &e.split_distance_m, Bound::kPositive),
      Number("extraction", "merge_max_angle_rad", &e.merge_max_angle_rad),
      Number("extraction", "merge_max_mahalanobis2", &e.merge_max_mahalanobis2),
      {"extraction", "min_points", nullptr, &e.min_points, nullptr, Bound::kFinite, 2},
      Number("extraction", "min_length_m", &e.min_length_m),
      Number("extraction", "max_residual_rms_m", &e.max_residual_rms_m, Bound::kPositive),
      Number("extraction", "sigma_range_m", &e.sigma_range_m, Bound::kPositive),
      Number("extraction", "sigma_bearing_rad", &e.sigma_bearing_rad, Bound::kPositive),
      Number("extraction", "wall_sigma_rho_m", &e.wall_sigma_rho_m),
      Number("extraction", "wall_sigma_alpha_rad", &e.wall_sigma_alpha_rad),
      Number("extraction", "min_corner_angle_rad", &e.min_corner_angle_rad),
      Number("extraction", "max_corner_angle_rad", &e.max_corner_angle_rad),
      Number("extraction", "max_corner_endpoint_distance_m", &e.max_corner_endpoint_distance_m),
      Number("lines", "gate_chi2", &l.gate_chi2, Bound::kPositive),
      Number("lines", "new_landmark_chi2", &l.new_landmark_chi2, Bound::kPositive),
      Number("lines", "overlap_margin_m", &l.overlap_margin_m),
      Number("lines", "min_new_length_m", &l.min_new_length_m),
      Number("lines", "new_min_separation_rho_m", &l.new_min_separation_rho_m),
      Number("lines", "new_min_separation_alpha_rad", &l.new_min_separation_alpha_rad),
      Number("lines", "min_rho_m", &p.ekf.min_line_rho_m),
      Number("corners", "gate_chi2", &p.ekf.corners.gate_chi2, Bound::kPositive),
      Number("corners", "new_landmark_chi2", &p.ekf.corners.new_landmark_chi2, Bound::kPositive),
      Number("corners", "reach_m", &p.ekf.corner_reach_m, Bound::kPositive),
      {"", "accuracy_ratio_every", nullptr, &p.accuracy_ratio_every, nullptr, Bound::kFinite, 0},
      Number("", "max_wall_time_s", &p.max_wall_time_s, Bound::kPositive, true),
      Number("", "flops_per_second", &p.flops_per_second, Bound::kPositive),
  };
}

const std::vector<std::string> kSections = {"selection", "odometry", "extraction", "lines",
                                            "corners"};

std::vector<std::string> KeysOf(const std::vector<Field>& fields, const std::string& section) {
  std::vector<std::string> keys;
  if (section.empty()) keys = kSections;
  if (section == "selection") keys.push_back("policy");
  for (const Field& f : fields) {
    if (f.section == section) keys.push_back(f.key);
  }
  return keys;
}

void ReadField(const Section& s, const Field& f) {
  if (f.number && f.infinity_allowed && s.Has(f.key) && s.Get(f.key).IsNull()) {
    *f.number = std::numeric_limits<double>::infinity();
  } else if (f.number) {
    s.Read(f.key, f.number, f.bound);
  } else if (f.integer) {
    s.Read(f.key, f.integer, f.min);
  } else {
    s.Read(f.key, f.flag);
  }
}

nlohmann::json FieldJson(const Field& f) {
  if (f.integer) return *f.integer;
  if (f.flag) return *f.flag;
  return std::isfinite(*f.number) ? nlohmann::json(*f.number) : nlohmann::json(nullptr);
}

}  // namespace

FeatureLogParams LoadFeatureLogConfig(const std::filesystem::path& path,
                                      const FeatureLogParams& defaults) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  FeatureLogParams p = defaults;
  const std::vector<Field> fields = Fields(p);
  const Section root(yaml, path.string(), "", KeysOf(fields, ""));
  for (const std::string& name : kSections) {
    const Section s = root.Child(name, KeysOf(fields, name));
    for (const Field& f : fields) {
      if (f.section == name) ReadField(s, f);
    }
    if (name == "selection") {
      p.selection = static_cast<SelectionKind>(
          config::ReadChoice(s, "policy", kPolicies, static_cast<int>(p.selection)));
    }
  }
  for (const Field& f : fields) {
    if (std::string(f.section).empty()) ReadField(root, f);
  }
  return p;
}

nlohmann::json FeatureLogParamsJson(const FeatureLogParams& params) {
  FeatureLogParams p = params;
  nlohmann::json j;
  for (const Field& f : Fields(p)) {
    if (std::string(f.section).empty()) {
      j[f.key] = FieldJson(f);
    } else {
      j[f.section][f.key] = FieldJson(f);
    }
  }
  j["selection"]["policy"] = SelectionKindName(p.selection);
  return j;
}

}  // namespace slamkit
