#include "slamkit/runners/common/log_scoring.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <exception>

namespace slamkit {

LogEvaluation EvaluateOnLog(const Trajectory& estimate, const Trajectory& odometry,
                            std::vector<PoseRelation> relations,
                            const std::optional<Trajectory>& reference,
                            const LogScoringParams& params) {
  LogEvaluation e;
  try {
    // A run that stopped early, or over --max-scans, is scored on what it covered.
    if (params.partial_log || estimate.size() < odometry.size()) {
      relations = RelationsCovered(estimate, relations);
    }
    if (!relations.empty()) {
      e.relations = EvaluateRelations(estimate, relations);
      e.odometry_relations = EvaluateRelations(odometry, relations);
    }
    if (reference) {
      Trajectory covered = *reference;
      if (params.pair_by == PairBy::kIndex && covered.size() > estimate.size()) {
        covered.resize(estimate.size());
      }
      Trajectory odometry_covered(odometry.begin(),
                                  odometry.begin() + std::min(odometry.size(), estimate.size()));
      e.reference = CompareWithReference(estimate, covered, params.pair_by);
      e.odometry_reference = CompareWithReference(odometry_covered, covered, params.pair_by);
    }
  } catch (const std::exception& ex) {
    e.error = ex.what();
  }
  return e;
}

void AddErrorMetrics(const RelationErrorStats* relations, const ReferenceComparison* reference,
                     nlohmann::json& j) {
  if (relations) {
    j["relations"] = relations->count;
    j["relations_trans_mean_m"] = relations->trans_mean_m;
    j["relations_trans_std_m"] = relations->trans_std_m;
    j["relations_rot_mean_deg"] = relations->rot_mean_deg;
    j["relations_rot_std_deg"] = relations->rot_std_deg;
  }
  if (reference) {
    j["ate_rmse_m"] = reference->ate.rmse_m;
    j["ate_mean_m"] = reference->ate.mean_m;
    j["ate_max_m"] = reference->ate.max_m;
    j["rpe_trans_mean_m"] = reference->rpe.trans_mean_m;
    j["rpe_trans_std_m"] = reference->rpe.trans_std_m;
    j["rpe_rot_mean_deg"] = reference->rpe.rot_mean_deg;
    j["rpe_rot_std_deg"] = reference->rpe.rot_std_deg;
  }
}

void AddBaselineMetrics(const LogEvaluation& e, nlohmann::json& metrics) {
  if (e.odometry_relations) {
    metrics["odometry_relations_trans_mean_m"] = e.odometry_relations->trans_mean_m;
    metrics["odometry_relations_rot_mean_deg"] = e.odometry_relations->rot_mean_deg;
  }
  if (e.odometry_reference) {
    metrics["odometry_ate_rmse_m"] = e.odometry_reference->ate.rmse_m;
    metrics["odometry_rpe_trans_mean_m"] = e.odometry_reference->rpe.trans_mean_m;
    metrics["odometry_rpe_rot_mean_deg"] = e.odometry_reference->rpe.rot_mean_deg;
  }
  if (!e.error.empty()) metrics["evaluation_error"] = e.error;
}

Trajectory LoggedTrajectory(const CarmenLog& log) {
  Trajectory out;
  out.reserve(log.scans.size());
  for (const LaserScan& scan : log.scans) out.push_back({scan.t_s, scan.logged_pose});
  return out;
}

Trajectory OdometryTrajectory(const CarmenLog& log) {
  Trajectory out;
  out.reserve(log.scans.size());
  for (const LaserScan& scan : log.scans) out.push_back({scan.t_s, scan.odometry});
  return out;
}

double PeakRssMib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

nlohmann::json HeadingDriftJson(const HeadingDriftFit& fit, const HeadingDriftParams& params) {
  return {{"fitted_rad_per_m", fit.drift_rad_per_m},
          {"rms_before_rad", fit.rms_before_rad},
          {"rms_after_rad", fit.rms_after_rad},
          {"windows", fit.windows},
          {"window_steps", params.window_steps}};
}

}  // namespace slamkit
