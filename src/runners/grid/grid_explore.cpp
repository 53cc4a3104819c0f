#include "slamkit/runners/grid/grid_explore.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"
#include "slamkit/io/grid_writers.hpp"
#include "slamkit/models/line_sensor.hpp"
#include "slamkit/models/motion_model.hpp"
#include "slamkit/sim/floor_plan_grid.hpp"

namespace slamkit {
namespace {

double DistanceToWalls(const FloorPlan& plan, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const WallSegment& w : plan.walls) {
    best = std::min(best, std::sqrt(PointSegmentDistanceSq(p, w.first, w.second)));
  }
  return best;
}

double KnownArea(const OccupancyGrid& grid) {
  long cells = 0;
  ForEachKnownCell(grid, [&](const CellIndex&, OccupancyGrid::CellValue) { ++cells; });
  return static_cast<double>(cells) * grid.resolution() * grid.resolution();
}

// The robot, its filter and its explorer through one run (SPEC S4's simulated experiment).
class Exploration {
 public:
  Exploration(const FloorPlan& plan, const Pose2& start, std::uint64_t sim_seed,
              const GridSlamConfig& slam, const GridExploreParams& params)
      : plan_(plan), params_(params), rng_(sim_seed), truth_(start), odometry_(start),
        explorer_(params.explorer) {
    RbpfGridSlamParams rbpf = slam.rbpf;
    rbpf.initial_pose = start;  // the start pose is known: the map is in the world frame
    // A beam with no return says the first wall is beyond the laser's range, not beyond the
    // filter's usable range: the robot knows its own sensor.
    rbpf.no_return_ray_length_m = std::min(rbpf.no_return_ray_length_m, params.laser.range_limit_m);
    if (params.predict) {
      auto predictive = std::make_unique<PredictiveGridSlam>(
          rbpf, params.prediction, MakeStructurePredictor(params.predictor));
      predictive_ = predictive.get();
      slam_ = std::move(predictive);
    } else {
      slam_ = std::make_unique<RbpfGridSlam>(rbpf);
    }
  }

  void Run(const std::function<void(double, double)>& progress, GridExploreResult& out);
  void Finish(GridExploreResult& out);

 private:
  void Sense(double t_s, GridExploreResult& out);
  Control Decide(double t_s);
  void Move(const Control& u, GridExploreResult& out);

  const FloorPlan& plan_;
  GridExploreParams params_;
  Rng rng_;
  Pose2 truth_, odometry_;
  GridExplorer explorer_;
  std::unique_ptr<GridSlam> slam_;
  PredictiveGridSlam* predictive_ = nullptr;
  UnicycleModel model_;
};

void Exploration::Run(const std::function<void(double, double)>& progress,
                      GridExploreResult& out) {
  for (long k = 0;; ++k) {
    const double t_s = static_cast<double>(k) * params_.dt_s;
    Sense(t_s, out);
    if (progress && k % 100 == 0) progress(t_s, params_.max_time_s);
    if (t_s >= params_.max_time_s) break;
    const Control u = Decide(t_s);
    if (explorer_.done()) {
      out.finished = true;
      break;
    }
    Move(u, out);
  }
  out.exploration_time_s = out.truth.back().t_s;
  out.targets = explorer_.targets_chosen();
}

void Exploration::Sense(double t_s, GridExploreResult& out) {
  LaserScan scan = SimulateScan(plan_, truth_, params_.laser, rng_);
  scan.t_s = t_s;
  scan.odometry = odometry_;
  scan.logged_pose = odometry_;
  slam_->ProcessScan(scan);
  out.truth.push_back({t_s, truth_});
  out.odometry.push_back({t_s, odometry_});
}

// The explorer sees the SLAM estimate and map only. With P-SLAM it plans on the map with the
// best particle's predicted cells filled in where the map is unknown: a region enclosed by
// predicted walls has no frontier left, and is not visited (SPEC S4). A new target starts a
// prediction there.
Control Exploration::Decide(double t_s) {
  if (predictive_ == nullptr) return explorer_.Step(slam_->CurrentPose(), slam_->BestMap(), t_s);
  const OccupancyGrid& map = slam_->BestMap();
  const OccupancyGrid* layer = predictive_->BestPredictedLayer();
  const OccupancyGrid planned = layer == nullptr ? map : WithPredictedCells(map, PredictedCells(map, layer));
  const Control u = explorer_.Step(slam_->CurrentPose(), planned, t_s);
  if (explorer_.target_changed() && explorer_.target()) {
    predictive_->RequestPrediction(planned.CellCenter(explorer_.target()->cell));
  }
  return u;
}

// The true robot moves as commanded; its odometry integrates the command with noise.
void Exploration::Move(const Control& u, GridExploreResult& out) {
  const Pose2 next = model_.Move(truth_, u, params_.dt_s);
  out.path_length_m += (next.translation() - truth_.translation()).norm();
  truth_ = next;
  // The simulated robot does not collide: how close it came is reported instead.
  out.closest_wall_m = std::min(out.closest_wall_m, DistanceToWalls(plan_, truth_.translation()));
  Control measured = u;
  measured[0] += rng_.Normal(0.0, params_.sigma_v_mps);
  measured[1] += rng_.Normal(0.0, params_.sigma_omega_radps);
  odometry_ = model_.Move(odometry_, measured, params_.dt_s);
}

void Exploration::Finish(GridExploreResult& out) {
  if (predictive_ != nullptr) predictive_->Flush();
  slam_->CheckOutputHealth();
  out.slam.trajectory = slam_->BestTrajectory();
  out.slam.map = slam_->BestMap();
  out.slam.scans = static_cast<int>(out.truth.size());
  const GridSlamStats stats = slam_->Stats();
  out.slam.updates = stats.updates;
  out.slam.resamples = stats.resamples;
  out.slam.heading_drift_in_use_rad_per_m = stats.heading_drift_in_use_rad_per_m;
  if (predictive_ == nullptr) return;
  out.predicted = PredictedCells(out.slam.map, predictive_->BestPredictedLayer());
  out.hypotheses = HypothesisRows(*predictive_, out.slam.map, params_.predictor);
}

void ScoreMaps(int tolerance_cells, GridExploreResult& out) {
  const OccupancyImage truth = RenderOccupancyImage(out.truth_map);
  MapComparisonParams scoring;
  scoring.dice_tolerance_cells = tolerance_cells;
  out.explored_vs_truth = CompareMaps(RenderOccupancyImage(out.slam.map), truth, scoring);
  out.combined_vs_truth = CompareMaps(
      RenderOccupancyImage(WithPredictedCells(out.slam.map, out.predicted)), truth, scoring);
  out.explored_area_m2 = KnownArea(out.slam.map);
  out.predicted_area_m2 = KnownArea(out.predicted);
}

}  // namespace

GridExploreResult RunGridExploration(const FloorPlan& plan, const Pose2& start,
                                     std::uint64_t sim_seed, const GridSlamConfig& slam,
                                     const GridExploreParams& params,
                                     const std::function<void(double, double)>& progress) {
  if (!(params.dt_s > 0.0) || !(params.max_time_s >= 0.0) || !(params.sigma_v_mps >= 0.0) ||
      !(params.sigma_omega_radps >= 0.0)) {
    throw std::invalid_argument("gridexplore: need dt_s > 0, max_time_s >= 0 and sigmas >= 0");
  }
  const auto wall_start = std::chrono::steady_clock::now();
  GridExploreResult out;
  // The true map first: a start on a wall or outside the plan is an input error before the run.
  try {
    out.truth_map = FloorPlanOccupancy(plan, slam.rbpf.grid, start.translation());
  } catch (const std::invalid_argument&) {
    throw InputError(fmt::format("gridexplore: the start ({}, {}) lies on a wall or outside the "
                                 "plan's walls", start.x(), start.y()));
  }
  Exploration exploration(plan, start, sim_seed, slam, params);
  exploration.Run(progress, out);
  exploration.Finish(out);
  out.slam.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  out.vs_truth = CompareWithReference(out.slam.trajectory, out.truth);
  out.odometry_vs_truth = CompareWithReference(out.odometry, out.truth);
  ScoreMaps(params.dice_tolerance_cells, out);
  return out;
}

namespace {

nlohmann::json MapComparisonJson(const MapComparison& c) {
  return {{"kl_divergence", c.kl_divergence},
          {"cell_accuracy", c.cell_accuracy},
          {"dice_occupied", c.dice_occupied},
          {"known_cells", c.known_cells}};
}

}  // namespace

nlohmann::json GridExploreMetrics(const GridExploreResult& result, const GridExploreParams& params,
                                  std::uint64_t sim_seed, const GridSlamConfig& slam,
                                  double peak_rss_mib) {
  nlohmann::json j = GridMetrics(result.slam, slam, nullptr, &result.vs_truth, peak_rss_mib);
  j["sim_seed"] = sim_seed;
  j["predict"] = params.predict;
  j["finished"] = result.finished;
  j["exploration_time_s"] = result.exploration_time_s;
  j["path_length_m"] = result.path_length_m;
  j["closest_wall_m"] = result.closest_wall_m;
  j["targets"] = result.targets;
  j["odometry_ate_rmse_m"] = result.odometry_vs_truth.ate.rmse_m;
  j["explored_vs_truth"] = MapComparisonJson(result.explored_vs_truth);
  j["combined_vs_truth"] = MapComparisonJson(result.combined_vs_truth);
  j["explored_area_m2"] = result.explored_area_m2;
  j["predicted_area_m2"] = result.predicted_area_m2;
  j["hypotheses"] = result.hypotheses.size();
  j["hypotheses_by_fate"] = HypothesisFateCounts(result.hypotheses);
  return j;
}

}  // namespace slamkit
