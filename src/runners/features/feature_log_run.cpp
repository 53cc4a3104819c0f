#include "slamkit/runners/features/feature_log_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "slamkit/features/scan_features.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/runners/common/log_scoring.hpp"
#include "slamkit/runners/features/feature_log_config.hpp"

namespace slamkit {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// The odometry increment as the control of an OdometryModel, with its covariance.
ControlCovariance IncrementNoise(const Pose2& delta, const FeatureLogParams& p) {
  const Eigen::Vector3d sigma =
      OdometryNoiseSigmas(delta, p.odometry_noise)
          .cwiseMax(Eigen::Vector3d(p.min_sigma_xy_m, p.min_sigma_xy_m, p.min_sigma_theta_rad));
  return sigma.cwiseAbs2().asDiagonal();
}

bool MovedEnough(const Pose2& delta, const FeatureLogParams& p) {
  return delta.translation().norm() >= p.linear_update_m ||
         std::abs(delta.theta()) >= p.angular_update_rad;
}

// `gate_chi2` and `new_chi2` are the association's two gates (LineAssociationParams,
// AssociationParams): a dropped sighting's distance to its nearest landmark says why it was.
void Count(const std::vector<AssociationDecision>& decisions, double gate_chi2, double new_chi2,
           SightingCounts* counts) {
  for (const AssociationDecision& d : decisions) {
    if (d.kind == AssociationDecision::Kind::kMatched) {
      ++counts->matched;
    } else if (d.kind == AssociationDecision::Kind::kNew) {
      ++counts->created;
    } else if (d.distance_chi2 <= gate_chi2) {
      ++counts->taken;
    } else if (d.distance_chi2 <= new_chi2) {
      ++counts->ambiguous;
    } else {
      ++counts->unmatched;
    }
  }
}

nlohmann::json CountsJson(const SightingCounts& c) {
  return {{"matched", c.matched},
          {"new", c.created},
          {"dropped_taken", c.taken},
          {"dropped_ambiguous", c.ambiguous},
          {"dropped_unmatched", c.unmatched}};
}

// One processed scan: the prediction by the odometry since the last one, then SPEC S1's
// correction (features, association, selection, updates, augmentation), timed.
void ProcessScan(const LaserScan& scan, const Pose2& delta, bool first, const FeatureLogParams& p,
                 FeatureEkfSlam& slam, FeatureLogResult* out) {
  if (!first) {
    Control u(3);
    u << delta.x(), delta.y(), delta.theta();
    const ControlCovariance Q = IncrementNoise(delta, p);
    slam.Predict(u, 0.0, &Q);
  }
  slam.SetSelectionDiagnostics(p.accuracy_ratio_every > 0 &&
                               out->updates % p.accuracy_ratio_every == 0);
  const auto start = Clock::now();
  const FeatureDecisions d =
      slam.Update(ToRobotFrame(ExtractFeatures(scan, p.extraction), scan.laser_offset));
  const double seconds = SecondsSince(start);
  Count(d.lines, p.ekf.lines.gate_chi2, p.ekf.lines.new_landmark_chi2, &out->lines_seen);
  Count(d.corners, p.ekf.corners.gate_chi2, p.ekf.corners.new_landmark_chi2, &out->corners_seen);
  out->correction_time_s += seconds;
  out->correction_time_max_s = std::max(out->correction_time_max_s, seconds);
  const SelectionStats& stats = slam.LastSelectionStats();
  out->modelled_time_s +=
      CorrectionFlops(p.selection, stats, slam.ekf().StateSize()) / p.flops_per_second;
  out->candidates += stats.candidates;
  out->applied += stats.applied;
  if (const std::optional<double> accuracy = stats.accuracy()) out->accuracy.push_back(*accuracy);
  ++out->updates;
}

// How far the log's laser sees features: its largest return, within the usable range. The
// compressed updates' area reaches that far (FeatureEkfSlamParams::area_reach_m).
double FeatureReach(const CarmenLog& log, const LineExtractionParams& extraction) {
  double farthest = 0.0;
  for (const LaserScan& scan : log.scans) {
    for (int i = 0; i < static_cast<int>(scan.ranges_m.size()); ++i) {
      if (scan.IsReturn(i)) farthest = std::max(farthest, double(scan.ranges_m[i]));
    }
  }
  return std::max(1.0, std::min(farthest, extraction.max_usable_range_m));
}

// metrics.json's filter_counters: what compressed updates cost (empty with dense ones).
nlohmann::json CompressionJson(const CompressionStats& s, EkfUpdateMode update) {
  if (update != EkfUpdateMode::kCompressed) return nlohmann::json::object();
  return {{"global_updates", s.global_updates},
          {"global_update_s", s.global_update_s},
          {"max_active_size", s.max_active_size}};
}

}  // namespace

LineExtractionParams FeatureLogParams::LogExtractionDefaults() {
  LineExtractionParams p;
  // SPEC S1 uses 10 m of its 30 m laser; on the logs a hall's far walls, long lines that hold
  // the heading, lie beyond that: 20 m is the best of 10, 15, 20 and 30 on intel.clf and
  // freiburg-101, and no worse on CSAIL (docs/feature_slam_logs.md).
  p.max_usable_range_m = 20.0;
  // Real walls are not the straight lines of 1 cm beam noise the fit assumes (clutter, doors,
  // glass, the laser's bias): with the simulator's values the lines' covariances are too tight
  // for the next sighting of the same wall, which then starts a second landmark and the map
  // bends. Chosen on the six logs of docs/feature_slam_logs.md (intel.clf and five of suite/).
  p.sigma_range_m = 0.05;
  p.wall_sigma_rho_m = 0.1;
  p.wall_sigma_alpha_rad = 0.03;
  return p;
}

FeatureLogResult RunFeatureSlamOnLog(const CarmenLog& log, const FeatureLogParams& params,
                                     const std::function<void(int, int)>& progress) {
  if (log.scans.empty()) {
    throw InputError("features: the log has no laser scan (no FLASER/ROBOTLASER1/RAWLASER line)");
  }
  const auto start = Clock::now();
  FeatureEkfSlamParams ekf = params.ekf;
  ekf.area_reach_m = FeatureReach(log, params.extraction);
  FeatureEkfSlam slam(ekf, std::make_unique<OdometryModel>(),
                      MakeSelectionPolicy(params.selection, params.covariance, params.entropy));
  FeatureLogResult out;
  out.scans = static_cast<int>(log.scans.size());
  Pose2 last_odometry = log.scans.front().odometry;
  for (int i = 0; i < out.scans; ++i) {
    const LaserScan& scan = log.scans[i];
    const Pose2 delta = last_odometry.Between(scan.odometry);
    if (i == 0 || MovedEnough(delta, params)) {
      ProcessScan(scan, delta, i == 0, params, slam, &out);
      last_odometry = scan.odometry;
      AppendWorldPoints(scan, slam.pose(), params.extraction.max_usable_range_m, &out.points);
      out.trajectory.push_back({scan.t_s, slam.pose()});
    } else {
      out.trajectory.push_back({scan.t_s, slam.pose().Compose(delta)});
    }
    if (progress && (i % 100 == 99 || i + 1 == out.scans)) progress(i + 1, out.scans);
    if (SecondsSince(start) > params.max_wall_time_s && i + 1 < out.scans) {
      out.stopped_early = true;
      break;
    }
  }
  slam.Synchronise();
  slam.CheckOutputHealth();
  out.compression = slam.Compression();
  out.lines = MappedLines(slam);
  out.corners = MappedCorners(slam);
  out.state_size = slam.ekf().StateSize();
  out.wall_time_s = SecondsSince(start);
  return out;
}

nlohmann::json FeatureLogMetrics(const FeatureLogResult& r, const FeatureLogParams& params,
                                 const RelationErrorStats* relations,
                                 const ReferenceComparison* reference) {
  double accuracy_sum = 0.0;
  for (double a : r.accuracy) accuracy_sum += a;
  nlohmann::json j = {
      {"selection", SelectionKindName(params.selection)},
      {"scans", r.scans},
      {"scans_reached", r.trajectory.size()},
      {"updates", r.updates},
      {"stopped_early", r.stopped_early},
      {"lines", r.lines.size()},
      {"corners", r.corners.size()},
      {"state_size", r.state_size},
      {"filter_counters", CompressionJson(r.compression, params.ekf.update)},
      {"line_sightings", CountsJson(r.lines_seen)},
      {"corner_sightings", CountsJson(r.corners_seen)},
      {"wall_time_s", r.wall_time_s},
      {"correction_time_s", r.correction_time_s},
      {"correction_time_max_s", r.correction_time_max_s},
      {"modelled_time_s", r.modelled_time_s},
      {"candidates_per_update", r.updates > 0 ? double(r.candidates) / r.updates : 0.0},
      {"applied_per_update", r.updates > 0 ? double(r.applied) / r.updates : 0.0},
      {"accuracy_ratio_mean",
       r.accuracy.empty() ? nlohmann::json() : nlohmann::json(accuracy_sum / r.accuracy.size())},
      {"params", FeatureLogParamsJson(params)}};
  AddErrorMetrics(relations, reference, j);
  return j;
}

}  // namespace slamkit
