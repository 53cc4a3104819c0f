#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <vector>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/eval/trajectory_errors.hpp"
#include "slamkit/io/carmen_reader.hpp"
#include "slamkit/models/odometry_sampling.hpp"
#include "slamkit/runners/features/explore_run.hpp"
#include "slamkit/runners/features/feature_exploration.hpp"

namespace slamkit {

// The line-and-corner EKF-SLAM of SPEC S1 on a laser log: the log's odometry as the motion, no
// exploration. Defaults chosen on intel.clf and suite/csail.log.gz (docs/feature_slam_logs.md).
struct FeatureLogParams {
  FeatureEkfSlamParams ekf;
  LineExtractionParams extraction = LogExtractionDefaults();
  SelectionKind selection = SelectionKind::kCovariance;
  CovarianceSelectionParams covariance;
  EntropySelectionParams entropy;
  // The increment's noise grows with the distance and the turn (OdometryNoiseSigmas), each σ
  // floored at min_sigma_*.
  OdometryNoiseParams odometry_noise{0.1, 0.1, 0.1, 0.1};
  double min_sigma_xy_m = 0.005;
  double min_sigma_theta_rad = 0.002;
  // A scan is processed once the odometry has moved this far or turned this much since the
  // last processed one (the others are carried by the odometry), as the grid filter does.
  double linear_update_m = 0.2;
  double angular_update_rad = 0.1;
  // Every how many processed scans the step also runs the full update, on the marginal of the
  // matched blocks, for the accuracy ratio (SPEC S1, Eq. 24); 0: never. Its cost (O(k²) in the
  // matched blocks' k entries) is in the measured times.
  int accuracy_ratio_every = 1;
  // The run stops after this much wall time (the dense entropy policy's O(n³) per candidate can
  // make a whole log impractical) and keeps what it computed.
  double max_wall_time_s = std::numeric_limits<double>::infinity();
  // The modelled cost's machine (as FeatureSlamParams::flops_per_second).
  double flops_per_second = 1.0e9;

  static LineExtractionParams LogExtractionDefaults();
};

// How the sightings of one kind fared over a run: matched to a landmark, new, or dropped, which
// is one of: compatible with a landmark another sighting of the scan took (`taken`), between
// the match and new-landmark gates (`ambiguous`), or compatible with none yet not allowed to
// start a landmark (`unmatched`: too short, or too near one).
struct SightingCounts {
  long long matched = 0;
  long long created = 0;
  long long taken = 0;
  long long ambiguous = 0;
  long long unmatched = 0;
};

struct FeatureLogResult {
  Trajectory trajectory;  // one pose per scan reached, t as in the log
  std::vector<MappedLine> lines;
  std::vector<Eigen::Vector2d> corners;
  std::vector<Eigen::Vector2d> points;  // the processed scans' returns, placed by the estimate
  int scans = 0;                        // of the log
  int updates = 0;                      // scans processed
  bool stopped_early = false;           // max_wall_time_s reached before the log's end
  double wall_time_s = 0.0;
  double correction_time_s = 0.0;  // Σ of the updates' wall time
  double correction_time_max_s = 0.0;
  double modelled_time_s = 0.0;  // Σ counted work / flops_per_second
  long long candidates = 0;      // matched observations offered to the policy
  long long applied = 0;
  SightingCounts lines_seen;
  SightingCounts corners_seen;
  std::vector<double> accuracy;  // per sampled step with something to reduce
  int state_size = 0;            // at the end
  CompressionStats compression;  // with compressed updates (ekf.update)
};

// Runs the filter over `log`'s scans from the origin; `progress(done, total)` every few scans.
// Throws InputError for a log without scans.
FeatureLogResult RunFeatureSlamOnLog(const CarmenLog& log, const FeatureLogParams& params,
                                     const std::function<void(int, int)>& progress = {});

// metrics.json of such a run (README's output contract), with the parameters as
// FeatureLogParamsJson writes them; `relations` and `reference` may be null.
nlohmann::json FeatureLogMetrics(const FeatureLogResult& result, const FeatureLogParams& params,
                                 const RelationErrorStats* relations,
                                 const ReferenceComparison* reference);

}  // namespace slamkit
