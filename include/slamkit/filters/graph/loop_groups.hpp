#pragma once

#include <vector>

#include "slamkit/core/pose_graph.hpp"
#include "slamkit/optim/pose_graph_optimizer.hpp"

namespace slamkit {

// A robust loss discounts a closure whose residual is large at the estimate it starts from. That
// is what keeps a false closure from tearing the map, and also what keeps the first closures of
// a long loop, tens of metres off after hundreds of metres of drift, from ever pulling it shut.
// What tells the two apart is agreement: the closures a robot makes while it drives along a
// stretch it has mapped before put it where the chain between them says, relative to one
// another (Latif, Cadena and Neira, "Robust loop closing over time", IJRR 2013, clusters closures
// the same way). A group of such closures is tried: the graph is solved with the group alone,
// then whole from there, and the result kept when more closures agree with it than before.
struct LoopGroupParams {
  int min_size = 3;         // closures a group needs (0: no groups are tried)
  int max_node_gap = 30;    // closures this many nodes apart or more start another group
  // Two closures agree when the relative pose of their nodes as the closures place them is
  // within this of the relative pose the chain between the nodes gives.
  double max_translation_m = 0.3;
  double max_rotation_rad = 0.05;
  int max_groups = 3;  // groups tried per optimisation, largest first
  // A closure (an edge whose vertices are not consecutive) agrees with a solution when its
  // whitened squared residual is at most this: χ²(3)'s 99.7 % quantile.
  double agreement_chi2 = 14.16;
};

// Whether closure edge `edge` agrees with `poses` (vertex ids are the poses' indices).
bool ClosureAgrees(const PoseGraphEdge& edge, const std::vector<Pose2>& poses, double chi2);

// Groups of the closures `poses` disagrees with (indices into graph.edges) that agree with one
// another, largest first; the graph's vertex ids must be 0..n-1 in order.
std::vector<std::vector<int>> ConsistentLoopGroups(const PoseGraph& graph,
                                                   const std::vector<Pose2>& poses,
                                                   const LoopGroupParams& params);

// OptimizePoseGraph from `initial`, then for each group of ConsistentLoopGroups that holds an
// edge at or after `first_new_edge`: the chain and the group alone under the plain squared loss,
// from the solution, then the whole graph from there with `params`' losses; kept when more
// closures agree with it.
PoseGraphSolution OptimizeWithLoopGroups(const PoseGraph& graph, const std::vector<Pose2>& initial,
                                         const PoseGraphOptimizerParams& params,
                                         const LoopGroupParams& groups, int first_new_edge = 0);

}  // namespace slamkit
