#pragma once

#include <future>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/core/pose_graph.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/filters/graph/loop_closure.hpp"
#include "slamkit/filters/graph/loop_groups.hpp"
#include "slamkit/filters/graph/submaps.hpp"
#include "slamkit/filters/grid/scan_matcher.hpp"
#include "slamkit/filters/grid_slam.hpp"
#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/optim/grid_scan_refinement.hpp"
#include "slamkit/optim/robust_loss.hpp"

namespace slamkit {

// The front end's matcher: the grid filter's, with a rejected match rescued by kernels widened
// by 0.02 m per metre of range (ScanMatcherParams::rescue_sigma_per_m): 0.02 rad is the heading
// error the grid filter's motion model allows over the CARMEN suite's 1 m steps (str = 0.02
// rad/m), and one front end has no other hypothesis to fall back on (docs/posegraph.md).
inline ScanMatcherParams FrontEndMatcherParams() {
  ScanMatcherParams params;
  params.rescue_sigma_per_m = 0.02;
  return params;
}

struct GraphGridSlamParams {
  // The laser and the maps, as RbpfGridSlamParams has them (MakeGridSlam copies them from the
  // config's top level, which both back ends share).
  double usable_range_m = 50.0;
  bool misses_spare_scan_hits = true;
  double no_return_ray_length_m = std::numeric_limits<double>::infinity();
  OccupancyGridParams grid;
  Pose2 initial_pose;
  // The front end: each scan is matched against the matching submap from the previous scan's
  // pose moved by odometry; a match not accepted, even after the rescue (FrontEndMatcherParams),
  // keeps the odometry guess.
  ScanMatcherParams matcher = FrontEndMatcherParams();
  // A scan this far or further from the one before (by odometry) is sparse: between such scans
  // (a scan a metre, as the CARMEN suite's logs have) odometry can misjudge a turn by more than
  // the climb recovers, and one front end, unlike a particle set, has no other hypothesis. Its
  // match then first sweeps the heading over ± sparse_heading_sweep_rad and retries a poor
  // climb from other headings (ScanMatcherParams' heading_sweep_rad and
  // widen_below_score_fraction). Dense scans keep `matcher` as it is.
  double sparse_step_m = 0.5;
  double sparse_step_rad = 0.25;
  double sparse_heading_sweep_rad = 0.25;
  double sparse_widen_below_score_fraction = 0.5;
  // A dense scan's match that moves the odometry guess further than this is taken as a slide
  // along a corridor or onto a look-alike wall, not a correction, and the guess is kept: between
  // scans a few centimetres apart odometry is good to a few millimetres. 0: no such limit.
  double dense_max_correction_m = 0.2;
  // An accepted match refined by least squares on the submap interpolated between cells
  // (RefinePoseOnGrid, as Cartographer's front end does after its correlative match). Off
  // (max_iterations 0) by default: it made Intel's relations better and the sparse CARMEN
  // logs' figures scatter both ways, freiburg-campus's torn (docs/posegraph.md).
  GridRefinementParams refinement{.max_iterations = 0};
  // A scan becomes a graph node (inserted into the submaps, searched for loop closures) once the
  // front end has moved this far from the last node; the others only get a pose.
  double node_min_translation_m = 0.2;
  double node_min_rotation_rad = 0.1;
  SubmapParams submaps;
  // The measurement noise of the front end's motion between consecutive nodes.
  double local_sigma_xy_m = 0.01;
  double local_sigma_theta_rad = 0.0025;
  LoopClosureParams loop;
  // The loss of loop closures in the optimisation, so a false one cannot tear the map: DCS
  // (Agarwal et al. 2013), a closure costing at most 3Φ; Φ = 9 is a 3σ residual.
  RobustLossParams loop_loss{.kind = RobustLossKind::kDcs, .scale = 9.0};
  // Groups of closures that agree with one another, tried against the loss (loop_groups.hpp).
  LoopGroupParams loop_groups;
  // The loop-closure search and the optimisation run in a background thread on the graph as it
  // was every this many nodes; their result is taken in at the next such point (so a seed and a
  // log fix the output whatever the timing).
  int optimize_every_nodes = 100;
  int max_iterations = 30;  // Levenberg-Marquardt iterations per background optimisation
  int final_max_iterations = 200;
  // A robustness study: for each closure the search accepts, with this probability a false one
  // is added too, between a random node and a random earlier submap, its measurement drawn
  // uniformly within ±5 m and ±π (seeded by `seed`). 0: none, the normal use.
  double false_closure_fraction = 0.0;
  std::uint64_t seed = 1;
};

// Laser SLAM as a pose graph (Hess et al., ICRA 2016, as Cartographer does it): a front end
// matches each scan against a local submap and makes a node every so often; submaps of
// consecutive nodes are finished and searched for loop closures by branch and bound; the graph of
// nodes (front-end motion between consecutive nodes, closures to submaps' origin nodes under a
// robust loss) is optimised in the background on Ceres; the map is drawn from the nodes' scans at
// the optimised poses.
class GraphGridSlam final : public GridSlam {
 public:
  // Throws std::invalid_argument for params it cannot take (see SubmapStack, OccupancyGrid).
  explicit GraphGridSlam(const GraphGridSlamParams& params);
  ~GraphGridSlam() override;

  bool ProcessScan(const LaserScan& scan) override;
  // The last background job, a search of the nodes not yet searched and a final optimisation.
  void Finish() override;
  Pose2 CurrentPose() override;
  Trajectory BestTrajectory() override;
  const OccupancyGrid& BestMap() const override;
  GridSlamStats Stats() const override;
  void CheckOutputHealth() const override;
  const PoseGraph* FinalGraph() const override { return &graph_; }

  const std::vector<LoopClosure>& loop_closures() const { return closures_; }

 private:
  struct Node {
    Pose2 local;  // the front end's pose
    double driven_m = 0.0;  // path length from the first node, front-end poses
    std::shared_ptr<const LaserScan> scan;
    std::shared_ptr<const ScanPoints> points;
  };
  struct ScanRecord {
    double t_s;
    int anchor;     // the node at or before the scan
    Pose2 offset;   // the scan's local pose in the anchor's frame
  };
  struct JobResult;
  struct Job;

  Pose2 MatchFrontEnd(const ScanPoints& points, const Pose2& step);
  void AddNode(const LaserScan& scan, const Pose2& local, const ScanPoints& points);
  Pose2 GlobalPose(int node) const;
  void TakeJobResult();
  void StartJob(bool final);
  PoseGraph BuildGraph(int nodes) const;
  void CountDisagreeing();
  ScanInsertionParams Insertion() const {
    return {.usable_range_m = params_.usable_range_m,
            .misses_spare_scan_hits = params_.misses_spare_scan_hits,
            .no_return_ray_length_m = params_.no_return_ray_length_m};
  }
  void InjectFalseClosures(int accepted);

  GraphGridSlamParams params_;
  SubmapStack submaps_;
  std::vector<Node> nodes_;
  std::vector<ScanRecord> scans_;
  std::vector<std::shared_ptr<const Submap>> finished_;
  std::vector<LoopClosure> closures_;
  std::vector<Pose2> optimized_;  // global poses of the first optimized_.size() nodes
  int searched_nodes_ = 0;        // nodes handed to a search so far
  std::future<std::unique_ptr<JobResult>> job_;
  Pose2 last_local_, last_odometry_;
  PoseGraph graph_;  // after Finish
  mutable std::optional<OccupancyGrid> map_;
  GraphSlamStats stats_;
  Rng rng_;
  std::vector<bool> injected_;  // parallel to closures_: a false closure of the study
};

}  // namespace slamkit
