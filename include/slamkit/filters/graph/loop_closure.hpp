#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/pose_graph.hpp"
#include "slamkit/filters/graph/correlative_matcher.hpp"
#include "slamkit/filters/graph/submaps.hpp"
#include "slamkit/filters/grid/scan_matcher.hpp"

namespace slamkit {

// The matcher a loop closure is refined with once branch and bound has found it: a fine climb
// from the correlative match, which is only as good as its cell and angle steps.
inline ScanMatcherParams LoopRefinementParams() {
  ScanMatcherParams params;
  params.coarse_pass = false;
  params.linear_step_m = 0.025;
  params.angular_step_rad = 0.01;
  params.refinements = 4;
  return params;
}

// The search of a node's scan against a finished submap (Hess et al. 2016, Section V): branch
// and bound over a window around the node's current estimate that grows with the distance driven
// since the estimate was last tied to the map, then a fine climb.
struct LoopClosureParams {
  // min_score and the angular step of the correlative search; its window comes from below.
  CorrelativeMatcherParams matcher{.min_score = 0.55};
  // The window: ± (base + growth × d) in x and y, ± (base + growth × d) in θ, d the distance
  // driven since the node's chain last had a loop closure (or since the submap, if nearer),
  // capped at the maxima. The growth is the drift one expects of scan-matched odometry.
  double base_linear_window_m = 1.0;
  double linear_window_growth = 0.05;  // m per m driven
  double max_linear_window_m = 8.0;
  double base_angular_window_rad = 0.2;
  double angular_window_growth_rad_per_m = 0.005;
  double max_angular_window_rad = 0.6;
  // A submap is searched when one of its nodes lies within (window + this) of the node.
  double max_node_distance_m = 4.0;
  // The branch and bound uses the scan's points within this range (the refinement uses all): far
  // returns (through windows and doors) are sparse and noisy, and the angular step, which must
  // move the farthest point by no more than a cell, shrinks with the farthest point's range.
  double max_point_range_m = 15.0;
  // Every k-th node is searched (1: every node).
  int node_stride = 2;
  // A search over a wider window costs more (its area and angle) and is needed less often (a
  // closure at the end of a long loop is found from any of several nodes): a pair whose linear
  // window is k times the base one is searched on every k-th searched node only (true: so).
  bool thin_wide_windows = true;
  ScanMatcherParams refinement = LoopRefinementParams();
  // The closure's measurement noise: its information is diag(1/σ_xy², 1/σ_xy², 1/σ_θ²).
  double sigma_xy_m = 0.05;
  double sigma_theta_rad = 0.01;
};

// A constraint between a node and the node of a finished submap nearest to where it matched.
struct LoopClosure {
  int node = 0;
  int submap = 0;
  int anchor_node = 0;
  Pose2 relative;  // the node's pose in the anchor node's frame
  double score = 0.0;  // the correlative score of the match
  // The directions of `relative` the scan constrains: the fine match's
  // MatchConstraints::keep, a move (dx, dy, dθ) in the node's frame to its constrained part.
  Eigen::Matrix3d keep = Eigen::Matrix3d::Identity();
};

// diag(1/σ_xy², 1/σ_xy², 1/σ_θ²).
Eigen::Matrix3d DiagonalInformation(double sigma_xy_m, double sigma_theta_rad);

// A closure's edge from its anchor node to its node: σ (params' sigma_xy_m, sigma_theta_rad) in
// the directions its scan constrains and 100 σ in those it does not, since there (along a
// corridor) the match is where the search happened to stop, not a measurement.
PoseGraphEdge LoopClosureEdge(const LoopClosure& closure, const LoopClosureParams& params);

// The window LoopClosureParams gives after `driven_m` metres without a closure.
CorrelativeWindow LoopWindow(const LoopClosureParams& params, double driven_m);

// Whether `submap` is worth searching for a node at `node_in_local` (the node's estimate in the
// submap's local frame): one of its nodes within window + max_node_distance_m.
bool SubmapWithinReach(const Submap& submap, const Pose2& node_in_local,
                       const CorrelativeWindow& window, const LoopClosureParams& params);

// Matches `points` (a node's scan, robot frame) against `submap` around `node_in_local` (the
// node's estimate in the submap's local frame): branch and bound with `matcher` (built on the
// submap's grid) over `window`, then the refinement. Nothing when no pose scores min_score or
// the refinement fails.
std::optional<LoopClosure> MatchLoopClosure(int node, const Submap& submap,
                                            const CorrelativeMatcher& matcher,
                                            const ScanPoints& points, const Pose2& node_in_local,
                                            const CorrelativeWindow& window,
                                            const LoopClosureParams& params);

// One background search: nodes against the finished submaps, on the graph as it was when the
// search was handed off.
struct LoopSearchInput {
  std::vector<int> nodes;  // to search, ascending
  std::vector<std::shared_ptr<const ScanPoints>> points;  // parallel to `nodes`
  std::vector<Pose2> global;    // every node's estimate (index: node)
  std::vector<double> driven_m; // every node's path length from the first node
  std::vector<std::shared_ptr<const Submap>> submaps;  // finished, ascending index
  std::vector<LoopClosure> closures;  // accepted so far
  int nodes_per_submap = 1;           // node i lies in submaps i / N − 1 and i / N
};

// The distance driven that separates the first searched node from each submap (index: submap),
// along the chain of submaps or through accepted closures, which tie the submaps they join
// (Dijkstra): how far the node's estimate may have drifted from each submap.
std::vector<double> DriftDistances(const LoopSearchInput& input);

// Every searched node against every submap within reach (LoopWindow of its drift distance),
// ordered by node then submap. Submaps are searched in parallel, each matcher built once.
std::vector<LoopClosure> SearchLoopClosures(const LoopSearchInput& input,
                                            const LoopClosureParams& params);

}  // namespace slamkit
