#pragma once

#include <functional>
#include <optional>

#include <nlohmann/json.hpp>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/eval/heading_drift.hpp"
#include "slamkit/eval/trajectory_errors.hpp"
#include "slamkit/filters/grid_slam_factory.hpp"
#include "slamkit/filters/grid_slam.hpp"
#include "slamkit/io/carmen_reader.hpp"
#include "slamkit/runners/common/log_scoring.hpp"
#include "slamkit/runners/grid/hypotheses.hpp"

namespace slamkit {

// A grid SLAM over a whole CARMEN log.
struct GridRunResult {
  Trajectory trajectory;  // one pose per scan of the log, t as in the log
  OccupancyGrid map;      // the best particle's
  int scans = 0;
  int updates = 0;
  int resamples = 0;
  double wall_time_s = 0.0;
  // The log's odometry (as written, before odometry_heading_drift_rad_per_m) against the
  // trajectory, over windows of 100 scans: the drift to configure. Unset below one window.
  std::optional<HeadingDriftFit> odometry_heading_drift;
  // The calibration the filter ended with: the configured one, or with estimate_heading_drift
  // its running estimate.
  double heading_drift_in_use_rad_per_m = 0.0;
  // A graph back end's counts and optimised graph (unset and empty for the others).
  std::optional<GraphSlamStats> graph;
  PoseGraph pose_graph;
};

// `slam` over every scan of `log`; `progress(done, total)` is called every few scans from the
// calling thread. Throws InputError when the log has no scan or its values do not fit the
// filter's map, NumericalError when the filter's state is not healthy at the end.
GridRunResult RunGridSlam(const CarmenLog& log, GridSlam& slam,
                          const std::function<void(int, int)>& progress = {});
// The same with the filter `config` names (MakeGridSlam); its params' errors are InputErrors.
GridRunResult RunGridSlam(const CarmenLog& log, const GridSlamConfig& config,
                          const std::function<void(int, int)>& progress = {});

// P-SLAM on a log (SPEC S4): the grid RBPF of config.rbpf with structure prediction, the
// predictor choosing its own targets (the nearest reachable frontier of the best map) every
// prediction.request_every_updates updates. With prediction.deterministic_delay_scans > 0 a seed
// gives one run bit for bit.
struct PredictiveRunResult {
  GridRunResult run;
  std::vector<HypothesisRow> hypotheses;
  OccupancyGrid predicted;  // the best particle's predicted cells where its map is unknown
};
PredictiveRunResult RunPredictiveGridSlam(const CarmenLog& log, const GridSlamConfig& config,
                                          const GridPredictionConfig& prediction,
                                          const std::function<void(int, int)>& progress = {});

// metrics.json of a grid run (README's output contract); `relations` and `reference` may be null.
nlohmann::json GridMetrics(const GridRunResult& result, const GridSlamConfig& config,
                           const RelationErrorStats* relations,
                           const ReferenceComparison* reference, double peak_rss_mib);

}  // namespace slamkit
