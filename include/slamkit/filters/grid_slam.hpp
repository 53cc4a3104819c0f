#pragma once

#include <optional>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/core/pose_graph.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

// What a pose-graph back end reports besides GridSlamStats' counts.
struct GraphSlamStats {
  int nodes = 0;
  int submaps = 0;
  int matches_rescued = 0;         // front-end matches accepted only after the rescue
  int matches_kept_odometry = 0;   // front-end matches not taken: the odometry guess was kept
  int loop_closures = 0;              // accepted by the search
  int loop_closures_disagreeing = 0;  // of those, whose residual at the final solution is beyond 3σ
  int false_closures_injected = 0;    // a robustness study's (false_closure_fraction)
  int false_closures_disagreeing = 0;
  int optimizations = 0;
  double search_time_s = 0.0;         // in the background thread, summed
  double optimization_time_s = 0.0;
  double final_chi2 = 0.0;
};

// What a grid SLAM reports besides its estimate, for metrics.json and the console.
struct GridSlamStats {
  int updates = 0;    // scans that changed the estimate (the others only extend the path)
  int resamples = 0;  // a particle filter's resampling steps; 0 for a filter without particles
  // The odometry heading calibration in use at the end: the configured one, or its estimate.
  double heading_drift_in_use_rad_per_m = 0.0;
  std::optional<GraphSlamStats> graph;  // a pose-graph back end's
};

// The interface every laser SLAM on occupancy grids offers to the runners (a log, the suite, a
// simulated run), so that they take any of them: scans in, with their odometry; the best pose,
// path and map out; a health check before output. Implemented by RbpfGridSlam; a filter is made
// from a config by MakeGridSlam (filters/grid_slam_factory.hpp).
class GridSlam {
 public:
  virtual ~GridSlam() = default;

  // Takes the next scan (with its odometry, in the log's order); returns whether the estimate
  // was updated on it.
  virtual bool ProcessScan(const LaserScan& scan) = 0;
  // Completes the work a filter defers (a graph's last loop-closure search and optimisation);
  // the runners call it after the last scan. Scans may still follow.
  virtual void Finish() {}
  // The best estimate of the pose at the last scan.
  virtual Pose2 CurrentPose() = 0;
  // The best estimate's path: one pose per processed scan, t as the scan's.
  virtual Trajectory BestTrajectory() = 0;
  // The best estimate's map.
  virtual const OccupancyGrid& BestMap() const = 0;
  virtual GridSlamStats Stats() const = 0;
  // Throws NumericalError naming what failed if the estimate is not healthy (non-finite poses,
  // weights that cannot normalise), unless its params switched the check off.
  virtual void CheckOutputHealth() const = 0;
  // The optimised pose graph of a graph back end after Finish (null for the others).
  virtual const PoseGraph* FinalGraph() const { return nullptr; }
};

}  // namespace slamkit
