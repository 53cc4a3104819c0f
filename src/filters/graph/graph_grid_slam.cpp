#include "slamkit/filters/graph/graph_grid_slam.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "slamkit/core/numerical_error.hpp"
#include "slamkit/optim/pose_graph_optimizer.hpp"

namespace slamkit {
namespace {

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

// What a background job hands back: the closures it found, the optimised poses of the nodes the
// job's graph held, and its timings.
struct GraphGridSlam::JobResult {
  std::vector<LoopClosure> closures;
  std::vector<Pose2> poses;
  double chi2 = 0.0;
  double search_time_s = 0.0;
  double optimization_time_s = 0.0;
};

GraphGridSlam::GraphGridSlam(const GraphGridSlamParams& params)
    : params_(params),
      submaps_(params.submaps, params.grid, Insertion()),
      rng_(params.seed) {
  if (params.optimize_every_nodes < 1 || params.loop.node_stride < 1) {
    throw std::invalid_argument("graph: optimize_every_nodes and loop.node_stride must be >= 1");
  }
  if (!(params.false_closure_fraction >= 0.0 && params.false_closure_fraction <= 1.0)) {
    throw std::invalid_argument("graph: false_closure_fraction must be in [0, 1]");
  }
  MakeRobustLoss(params.loop_loss);  // a bad scale throws here, not in the background
}

GraphGridSlam::~GraphGridSlam() {
  if (job_.valid()) job_.wait();
}

// The front end (Hess et al. 2016, Section IV): the scan matched against the matching submap
// from the odometry guess; a node once it has moved far enough from the last.
bool GraphGridSlam::ProcessScan(const LaserScan& scan) {
  const ScanPoints points = PrepareScan(scan, params_.usable_range_m, params_.matcher);
  if (nodes_.empty()) {
    last_odometry_ = scan.odometry;
    last_local_ = params_.initial_pose;
    AddNode(scan, last_local_, points);
    scans_.push_back({scan.t_s, 0, Pose2()});
    return true;
  }
  const Pose2 step = last_odometry_.Between(scan.odometry);
  last_odometry_ = scan.odometry;
  last_local_ = MatchFrontEnd(points, step);
  const Pose2 moved = nodes_.back().local.Between(last_local_);
  const bool node = moved.translation().norm() >= params_.node_min_translation_m ||
                    std::abs(moved.theta()) >= params_.node_min_rotation_rad;
  if (node) AddNode(scan, last_local_, points);
  const int anchor = static_cast<int>(nodes_.size()) - 1;
  scans_.push_back({scan.t_s, anchor, nodes_.back().local.Between(last_local_)});
  return node;
}

// The front end's pose of a scan `step` (by odometry) after the last: its match against the
// matching submap from the odometry guess (rescued if need be: FrontEndMatcherParams), or the
// guess where the match is not accepted or, for a dense scan, moves the guess further than
// dense_max_correction_m (a slide, not a correction). The stats count both outcomes.
Pose2 GraphGridSlam::MatchFrontEnd(const ScanPoints& points, const Pose2& step) {
  const Pose2 guess = last_local_.Compose(step);
  ScanMatcherParams matcher = params_.matcher;
  const bool sparse = step.translation().norm() >= params_.sparse_step_m ||
                      std::abs(step.theta()) >= params_.sparse_step_rad;
  if (sparse) {
    matcher.heading_sweep_rad = params_.sparse_heading_sweep_rad;
    matcher.widen_below_score_fraction = params_.sparse_widen_below_score_fraction;
  }
  const MatchResult match = MatchScan(submaps_.MatchingSubmap()->grid, points, guess, matcher);
  const bool slid = !sparse && params_.dense_max_correction_m > 0.0 &&
                    (match.pose.translation() - guess.translation()).norm() >
                        params_.dense_max_correction_m;
  if (!match.accepted || slid) {
    ++stats_.matches_kept_odometry;
    return guess;
  }
  stats_.matches_rescued += match.rescued ? 1 : 0;
  if (params_.refinement.max_iterations == 0) return match.pose;
  return RefinePoseOnGrid(submaps_.MatchingSubmap()->grid, points.ends, match.pose,
                          params_.refinement);
}

void GraphGridSlam::AddNode(const LaserScan& scan, const Pose2& local, const ScanPoints& points) {
  const double driven =
      nodes_.empty() ? 0.0
                     : nodes_.back().driven_m +
                           (local.translation() - nodes_.back().local.translation()).norm();
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back({local, driven, std::make_shared<const LaserScan>(scan),
                    std::make_shared<const ScanPoints>(points)});
  for (auto& s : submaps_.Insert(index, local, scan)) finished_.push_back(std::move(s));
  map_.reset();
  if ((index + 1) % params_.optimize_every_nodes == 0) {
    TakeJobResult();
    StartJob(false);
  }
}

// A node's pose in the map: optimised, or the last optimised node's moved by the front end.
Pose2 GraphGridSlam::GlobalPose(int node) const {
  const int known = static_cast<int>(optimized_.size());
  if (node < known) return optimized_[static_cast<std::size_t>(node)];
  if (known == 0) return nodes_[static_cast<std::size_t>(node)].local;
  const Node& last = nodes_[static_cast<std::size_t>(known - 1)];
  return optimized_.back().Compose(last.local.Between(nodes_[static_cast<std::size_t>(node)].local));
}

PoseGraph GraphGridSlam::BuildGraph(int nodes) const {
  PoseGraph graph;
  const Eigen::Matrix3d local =
      DiagonalInformation(params_.local_sigma_xy_m, params_.local_sigma_theta_rad);
  for (int i = 0; i < nodes; ++i) {
    graph.vertices.push_back({i, GlobalPose(i)});
    if (i > 0) {
      graph.edges.push_back({i - 1, i,
                             nodes_[static_cast<std::size_t>(i - 1)].local.Between(
                                 nodes_[static_cast<std::size_t>(i)].local),
                             local});
    }
  }
  for (const LoopClosure& c : closures_) {
    if (c.node < nodes) graph.edges.push_back(LoopClosureEdge(c, params_.loop));
  }
  return graph;
}

// Hands the nodes not yet searched, and the graph as it is, to a background job: the search of
// those nodes against the finished submaps, then the optimisation of the graph with the closures
// found (Hess et al. 2016, Section V; the sparse pose adjustment on Ceres).
void GraphGridSlam::StartJob(bool final) {
  LoopSearchInput input;
  const int n = static_cast<int>(nodes_.size());
  for (int i = searched_nodes_; i < n; ++i) {
    if (i % params_.loop.node_stride != 0) continue;
    input.nodes.push_back(i);
    input.points.push_back(nodes_[static_cast<std::size_t>(i)].points);
  }
  searched_nodes_ = n;
  for (int i = 0; i < n; ++i) {
    input.global.push_back(GlobalPose(i));
    input.driven_m.push_back(nodes_[static_cast<std::size_t>(i)].driven_m);
  }
  input.submaps = finished_;
  input.closures = closures_;
  input.nodes_per_submap = params_.submaps.nodes_per_submap;
  PoseGraph graph = BuildGraph(n);
  PoseGraphOptimizerParams optimizer;
  optimizer.max_iterations = final ? params_.final_max_iterations : params_.max_iterations;
  optimizer.function_tolerance = 1e-9;
  optimizer.gradient_tolerance = 1e-10;
  optimizer.parameter_tolerance = 1e-9;
  optimizer.loop_closure_loss = params_.loop_loss;
  const LoopClosureParams loop = params_.loop;
  const LoopGroupParams groups = params_.loop_groups;
  job_ = std::async(std::launch::async, [input = std::move(input), graph = std::move(graph),
                                         optimizer, loop, groups]() mutable {
    auto result = std::make_unique<JobResult>();
    const auto start = std::chrono::steady_clock::now();
    result->closures = SearchLoopClosures(input, loop);
    result->search_time_s = Seconds(start);
    // Groups are tried where this search added to them: an older group has failed before.
    const int first_new = static_cast<int>(graph.edges.size());
    for (const LoopClosure& c : result->closures) graph.edges.push_back(LoopClosureEdge(c, loop));
    const PoseGraphSolution solution =
        OptimizeWithLoopGroups(graph, input.global, optimizer, groups, first_new);
    result->optimization_time_s = solution.time_s;
    result->poses = solution.poses;
    result->chi2 = solution.chi2;
    return result;
  });
}

void GraphGridSlam::TakeJobResult() {
  if (!job_.valid()) return;
  const std::unique_ptr<JobResult> result = job_.get();
  closures_.insert(closures_.end(), result->closures.begin(), result->closures.end());
  injected_.resize(closures_.size(), false);
  InjectFalseClosures(static_cast<int>(result->closures.size()));
  optimized_ = result->poses;
  stats_.optimizations += 1;
  stats_.search_time_s += result->search_time_s;
  stats_.optimization_time_s += result->optimization_time_s;
  stats_.final_chi2 = result->chi2;
  map_.reset();
}

// Each false closure joins a random node to a random submap finished before it, with a
// measurement no scan supports; the next optimisation sees it like any other.
void GraphGridSlam::InjectFalseClosures(int accepted) {
  if (params_.false_closure_fraction <= 0.0 || finished_.empty()) return;
  for (int k = 0; k < accepted; ++k) {
    if (rng_.Uniform() >= params_.false_closure_fraction) continue;
    const Submap& s = *finished_[static_cast<std::size_t>(rng_.Uniform(0, finished_.size()))];
    const int first = s.nodes.back() + 1, n = static_cast<int>(nodes_.size());
    if (first >= n) continue;
    const int node = first + static_cast<int>(rng_.Uniform(0, n - first));
    const Pose2 relative(rng_.Uniform(-5, 5), rng_.Uniform(-5, 5), rng_.Uniform(-M_PI, M_PI));
    closures_.push_back({node, s.index, s.origin_node, relative, 0.0});
    injected_.push_back(true);
  }
}

void GraphGridSlam::Finish() {
  TakeJobResult();
  for (auto& s : submaps_.FinishAll()) finished_.push_back(std::move(s));
  StartJob(true);
  TakeJobResult();
  graph_ = BuildGraph(static_cast<int>(nodes_.size()));
  CountDisagreeing();
}

// A closure disagrees with the solution when its whitened squared residual is beyond
// loop_groups.agreement_chi2 (χ²(3)'s 99.7 % quantile): the loss has discounted it rather than
// the map following it.
void GraphGridSlam::CountDisagreeing() {
  std::vector<Pose2> poses;
  for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) poses.push_back(GlobalPose(i));
  stats_.loop_closures_disagreeing = stats_.false_closures_disagreeing = 0;
  for (std::size_t i = 0; i < closures_.size(); ++i) {
    const PoseGraphEdge edge = LoopClosureEdge(closures_[i], params_.loop);
    if (ClosureAgrees(edge, poses, params_.loop_groups.agreement_chi2)) continue;
    ++(injected_[i] ? stats_.false_closures_disagreeing : stats_.loop_closures_disagreeing);
  }
}

Pose2 GraphGridSlam::CurrentPose() {
  if (scans_.empty()) return params_.initial_pose;
  const ScanRecord& r = scans_.back();
  return GlobalPose(r.anchor).Compose(r.offset);
}

Trajectory GraphGridSlam::BestTrajectory() {
  Trajectory out;
  out.reserve(scans_.size());
  for (const ScanRecord& r : scans_) out.push_back({r.t_s, GlobalPose(r.anchor).Compose(r.offset)});
  return out;
}

// The map of the nodes' scans at their graph poses, drawn when asked for.
const OccupancyGrid& GraphGridSlam::BestMap() const {
  if (!map_) {
    map_.emplace(params_.grid);
    const ScanInsertionParams insertion = Insertion();
    for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
      const LaserScan& scan = *nodes_[static_cast<std::size_t>(i)].scan;
      InsertScan(*map_, GlobalPose(i).Compose(scan.laser_offset), scan, insertion);
    }
  }
  return *map_;
}

GridSlamStats GraphGridSlam::Stats() const {
  GraphSlamStats graph = stats_;
  graph.nodes = static_cast<int>(nodes_.size());
  graph.submaps = static_cast<int>(submaps_.all().size());
  graph.false_closures_injected =
      static_cast<int>(std::count(injected_.begin(), injected_.end(), true));
  graph.loop_closures = static_cast<int>(closures_.size()) - graph.false_closures_injected;
  return {.updates = graph.nodes, .resamples = 0, .heading_drift_in_use_rad_per_m = 0.0,
          .graph = graph};
}

void GraphGridSlam::CheckOutputHealth() const {
  for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
    const Pose2 p = GlobalPose(i);
    if (!p.vector().allFinite()) {
      throw NumericalError("graph: node " + std::to_string(i) + "'s pose is not finite");
    }
  }
}

}  // namespace slamkit
