#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/eval/consistency.hpp"
#include "slamkit/filters/features/feature_ekf_slam.hpp"
#include "slamkit/models/line_sensor.hpp"
#include "slamkit/runners/features/exploration_config.hpp"
#include "slamkit/sim/floor_plan.hpp"

namespace slamkit {

// A line landmark of the final map: its world line, covariance and the extent it was seen over.
struct MappedLine {
  PolarLine line;
  Eigen::Matrix2d covariance;
  Eigen::Vector2d start_m;
  Eigen::Vector2d end_m;
};

// The final map of a line-and-corner EKF: its walls (merged landmarks left out) and corners.
std::vector<MappedLine> MappedLines(const FeatureEkfSlam& slam);
std::vector<Eigen::Vector2d> MappedCorners(const FeatureEkfSlam& slam);

// Appends the returns of `scan` nearer than `max_range_m` (ScanToBeamPoints), placed in the
// world from the robot pose `robot`: what a line map is drawn over.
void AppendWorldPoints(const LaserScan& scan, const Pose2& robot, double max_range_m,
                       std::vector<Eigen::Vector2d>* points);

struct ExploreResult {
  ExplorationRun run;
  std::vector<double> nees;  // pose NEES (3 dof) per step against the truth, from step 1
  // Per step (as run.truth), SPEC S1 Eq. 24's accuracy ratio of the step's selection, when
  // config.slam.ekf.selection_diagnostics is on (none for a step with nothing to reduce); empty
  // when it is off.
  std::vector<std::optional<double>> accuracy;
  std::vector<MappedLine> lines;               // one per wall (merged landmarks left out)
  std::vector<Eigen::Vector2d> corners;
  // Every scan's returns in the world, placed by the estimate of that step (for the map figure).
  std::vector<Eigen::Vector2d> scan_points;
  double wall_time_s = 0.0;
};

// SPEC S1's active loop with the line-and-corner EKF on `plan`, as `config` says.
ExploreResult RunFeatureExploration(const FloorPlan& plan, const ExplorationConfig& config);

// The figures of one exploration run: steps, simulated and SLAM times (total, per-step maximum,
// open-loop), the mean pose NEES with its 95 % band for one run's steps, mean and final position
// errors of the estimate and of the odometry, the map's line and corner counts, and the
// explorer's final mode.
struct ExploreFigures {
  int steps = 0;
  double elapsed_s = 0.0;
  double slam_time_total_s = 0.0;
  double slam_time_max_s = 0.0;
  double open_loop_time_s = 0.0;
  double mean_nees = 0.0;
  ChiSquareBand nees_band;
  double mean_error_m = 0.0;
  double final_error_m = 0.0;
  double odometry_mean_error_m = 0.0;
  double odometry_final_error_m = 0.0;
  int lines = 0;
  int corners = 0;
  ExplorerMode final_mode = ExplorerMode::kTurning;
  double wall_time_s = 0.0;
};
ExploreFigures ExploreFiguresOf(const ExploreResult& result);
const char* ExplorerModeName(ExplorerMode mode);
nlohmann::json ExploreFiguresJson(const ExploreFigures& figures);

// metrics.json of an exploration: the effective parameters (`params`) and ExploreFigures.
nlohmann::json ExploreMetrics(const ExploreResult& result, const ExplorationConfig& config);

}  // namespace slamkit
