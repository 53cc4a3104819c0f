#include "slamkit/runners/grid/grid_run.hpp"

#include <chrono>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

std::optional<HeadingDriftFit> FitLogOdometry(const CarmenLog& log, const Trajectory& estimate) {
  const HeadingDriftParams params;
  if (log.scans.size() < static_cast<std::size_t>(params.window_steps) + 1) return std::nullopt;
  std::vector<Pose2> steps;
  steps.reserve(log.scans.size() - 1);
  for (std::size_t i = 1; i < log.scans.size(); ++i) {
    steps.push_back(log.scans[i - 1].odometry.Between(log.scans[i].odometry));
  }
  return FitHeadingDrift(steps, estimate, params);
}

// The exceptions a filter throws for values it cannot take (its params', the log's), as the
// InputError a command reports with exit code 2. NumericalError is not one of them.
template <typename Body>
void AsInputErrors(Body body) {
  try {
    body();
  } catch (const std::invalid_argument& e) {  // the filter's parameters or the log's values
    throw InputError(std::string("grid: ") + e.what());
  } catch (const std::out_of_range& e) {  // a pose, odometry or laser offset outside the map
    throw InputError(std::string("grid: ") + e.what());
  } catch (const std::length_error& e) {  // a map larger than OccupancyGridParams allows
    throw InputError(std::string("grid: ") + e.what());
  }
}

void CheckHasScans(const CarmenLog& log) {
  if (log.scans.empty()) {
    throw InputError("grid: the log has no laser scan (no FLASER/ROBOTLASER1/RAWLASER line)");
  }
}

nlohmann::json GraphStatsJson(const GraphSlamStats& g) {
  return {{"nodes", g.nodes},
          {"submaps", g.submaps},
          {"matches_rescued", g.matches_rescued},
          {"matches_kept_odometry", g.matches_kept_odometry},
          {"loop_closures", g.loop_closures},
          {"loop_closures_disagreeing", g.loop_closures_disagreeing},
          {"false_closures_injected", g.false_closures_injected},
          {"false_closures_disagreeing", g.false_closures_disagreeing},
          {"optimizations", g.optimizations},
          {"search_time_s", g.search_time_s},
          {"optimization_time_s", g.optimization_time_s},
          {"final_chi2", g.final_chi2}};
}

}  // namespace

GridRunResult RunGridSlam(const CarmenLog& log, GridSlam& slam,
                          const std::function<void(int, int)>& progress) {
  CheckHasScans(log);
  const auto start = std::chrono::steady_clock::now();
  GridRunResult out;
  const int total = static_cast<int>(log.scans.size());
  AsInputErrors([&] {
    for (int i = 0; i < total; ++i) {
      slam.ProcessScan(log.scans[i]);
      if (progress && (i % 100 == 99 || i + 1 == total)) progress(i + 1, total);
    }
    slam.Finish();
    slam.CheckOutputHealth();
    out.trajectory = slam.BestTrajectory();
    out.map = slam.BestMap();
    const GridSlamStats stats = slam.Stats();
    out.updates = stats.updates;
    out.resamples = stats.resamples;
    out.heading_drift_in_use_rad_per_m = stats.heading_drift_in_use_rad_per_m;
    out.graph = stats.graph;
    if (const PoseGraph* graph = slam.FinalGraph()) out.pose_graph = *graph;
  });
  out.scans = total;
  out.odometry_heading_drift = FitLogOdometry(log, out.trajectory);
  out.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

GridRunResult RunGridSlam(const CarmenLog& log, const GridSlamConfig& config,
                          const std::function<void(int, int)>& progress) {
  CheckHasScans(log);  // before the filter's params, as the command always reported it
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<GridSlam> slam;
  AsInputErrors([&] { slam = MakeGridSlam(config); });
  GridRunResult out = RunGridSlam(log, *slam, progress);
  out.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

PredictiveRunResult RunPredictiveGridSlam(const CarmenLog& log, const GridSlamConfig& config,
                                          const GridPredictionConfig& prediction,
                                          const std::function<void(int, int)>& progress) {
  CheckHasScans(log);
  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<PredictiveGridSlam> slam;
  AsInputErrors([&] {
    slam = std::make_unique<PredictiveGridSlam>(config.rbpf, prediction.prediction,
                                                MakeStructurePredictor(prediction.predictor));
  });
  PredictiveRunResult out;
  out.run = RunGridSlam(log, *slam, progress);
  slam->Flush();
  out.hypotheses = HypothesisRows(*slam, out.run.map, prediction.predictor);
  out.predicted = PredictedCells(out.run.map, slam->BestPredictedLayer());
  out.run.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

nlohmann::json GridMetrics(const GridRunResult& r, const GridSlamConfig& config,
                           const RelationErrorStats* relations,
                           const ReferenceComparison* reference, double peak_rss_mib) {
  const RbpfGridSlamParams& params = config.rbpf;
  nlohmann::json j = {{"scans", r.scans},
                      {"updates", r.updates},
                      {"resamples", r.resamples},
                      {"particles", params.particles},
                      {"seed", params.seed},
                      {"linear_update_m", params.linear_update_m},
                      {"angular_update_rad", params.angular_update_rad},
                      {"track_between_updates", params.tracking_mode != TrackingMode::kOff},
                      {"motion_from_tracking",
                       params.tracking_mode == TrackingMode::kTrackedMotion},
                      {"gaussian_proposal", params.proposal == ProposalScheme::kGaussian},
                      {"usable_range_m", params.usable_range_m},
                      {"wall_time_s", r.wall_time_s},
                      {"scans_per_s", r.wall_time_s > 0 ? r.scans / r.wall_time_s : 0.0},
                      {"peak_rss_mib", peak_rss_mib}};
  AddErrorMetrics(relations, reference, j);
  if (r.odometry_heading_drift) {
    j["odometry_heading_drift"] = HeadingDriftJson(*r.odometry_heading_drift, {});
  }
  j["heading_drift_in_use_rad_per_m"] = r.heading_drift_in_use_rad_per_m;
  if (r.graph) j["graph"] = GraphStatsJson(*r.graph);
  return j;
}

}  // namespace slamkit
