#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "slamkit/eval/map_comparison.hpp"
#include "slamkit/filters/grid/predictive_grid_slam.hpp"
#include "slamkit/planning/grid_explorer.hpp"
#include "slamkit/planning/structure_predictor.hpp"
#include "slamkit/runners/grid/grid_run.hpp"
#include "slamkit/runners/grid/hypotheses.hpp"
#include "slamkit/sim/laser_sim.hpp"

namespace slamkit {

// Player/Stage's SICK LMS-200 model (the seed's simulator): 8 m range, 180°, here 180 beams.
inline LaserSimParams StageSickLaser() {
  LaserSimParams laser;
  laser.range_limit_m = 8.0;
  return laser;
}

// The explorer names the targets; each prediction is taken 10 scans (1 s) after its request, so
// that a seed gives one run bit for bit.
inline PredictiveGridSlamParams ExplorerDrivenPrediction() {
  PredictiveGridSlamParams params;
  params.automatic_targets = false;
  params.deterministic_delay_scans = 10;
  return params;
}

// SPEC S4's simulated experiments: a unicycle robot with a laser explores a floor plan, driven
// by GridExplorer on the SLAM estimate (never the truth), with or without P-SLAM's predictions.
struct GridExploreParams {
  double dt_s = 0.1;                // a control step and a scan
  double sigma_v_mps = 0.05;        // odometry noise per step, as gridsim's
  double sigma_omega_radps = 0.02;
  LaserSimParams laser = StageSickLaser();
  double max_time_s = 3600.0;       // the run stops here if the explorer has not finished
  // P-SLAM on: a prediction at every new exploration target, and the explorer plans on the map
  // with the predicted cells filled in, so that what is predicted is not visited. Off: plain
  // grid RBPF and full frontier coverage.
  bool predict = false;
  // The maps' Ψ against the true map counts a wall cell within this many cells of the other's
  // (MapComparisonParams): the true walls are rasterised from their lines, the mapped ones from
  // the beams' ends, on either side of the line.
  int dice_tolerance_cells = 1;
  GridExplorerParams explorer;
  StructurePredictorParams predictor;
  PredictiveGridSlamParams prediction = ExplorerDrivenPrediction();
};

struct GridExploreResult {
  GridRunResult slam;   // the trajectory (a pose per scan), the best map, counts, wall time
  Trajectory truth;     // parallel to slam.trajectory
  Trajectory odometry;
  ReferenceComparison vs_truth, odometry_vs_truth;
  bool finished = false;  // the explorer found no frontier left before max_time_s
  double exploration_time_s = 0.0;
  double path_length_m = 0.0;  // of the true path
  // The true path's least distance to a wall (the robot does not collide; a robot of radius
  // explorer.paths.robot_radius_m touched one where this is smaller).
  double closest_wall_m = std::numeric_limits<double>::infinity();
  int targets = 0;
  std::vector<HypothesisRow> hypotheses;
  OccupancyGrid predicted;  // the best particle's predicted cells where its map is unknown
  OccupancyGrid truth_map;  // FloorPlanOccupancy of the plan from the start
  MapComparison explored_vs_truth;  // the explored map against the true map
  MapComparison combined_vs_truth;  // explored plus predicted against the true map
  double explored_area_m2 = 0.0, predicted_area_m2 = 0.0;
};

// The experiment from `start` with Rng(sim_seed) for the robot's noise; the filter's own seed is
// slam.rbpf.seed. `progress(simulated_s, max_time_s)` every few steps.
GridExploreResult RunGridExploration(const FloorPlan& plan, const Pose2& start,
                                     std::uint64_t sim_seed, const GridSlamConfig& slam,
                                     const GridExploreParams& params,
                                     const std::function<void(double, double)>& progress = {});

// metrics.json: GridMetrics with the comparison against the truth, plus the exploration's
// figures (finished, exploration_time_s, path_length_m, closest_wall_m, targets), the maps against the truth
// (explored_* and combined_*: kl_divergence, cell_accuracy, dice_occupied), the areas and the
// hypotheses' counts by fate.
nlohmann::json GridExploreMetrics(const GridExploreResult& result, const GridExploreParams& params,
                                  std::uint64_t sim_seed, const GridSlamConfig& slam,
                                  double peak_rss_mib);

}  // namespace slamkit
