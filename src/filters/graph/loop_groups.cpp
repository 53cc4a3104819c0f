#include "slamkit/filters/graph/loop_groups.hpp"

#include <algorithm>
#include <cmath>

namespace slamkit {
namespace {

bool IsClosure(const PoseGraphEdge& e) { return std::abs(e.from - e.to) != 1; }

const Pose2& At(const std::vector<Pose2>& poses, int id) {
  return poses[static_cast<std::size_t>(id)];
}

// Where closure `e` puts its node, given its anchor's pose.
Pose2 ClosurePlacement(const PoseGraphEdge& e, const std::vector<Pose2>& poses) {
  return At(poses, e.from).Compose(e.measurement);
}

// Whether two closures place their nodes relative to one another as the chain does.
bool Agree(const PoseGraphEdge& a, const PoseGraphEdge& b, const std::vector<Pose2>& poses,
           const LoopGroupParams& params) {
  const Pose2 by_closures = ClosurePlacement(a, poses).Between(ClosurePlacement(b, poses));
  const Pose2 by_chain = At(poses, a.to).Between(At(poses, b.to));
  const Pose2 error = by_chain.Between(by_closures);
  return error.translation().norm() <= params.max_translation_m &&
         std::abs(error.theta()) <= params.max_rotation_rad;  // Pose2 keeps θ in (−π, π]
}

// The largest subset of `members` (edge indices) whose closures all agree pairwise, found
// greedily: the member that agrees with most, those agreeing with it, then the worst dropped
// until every pair agrees.
std::vector<int> AgreeingSubset(const PoseGraph& graph, const std::vector<Pose2>& poses,
                                const std::vector<int>& members, const LoopGroupParams& params) {
  const std::size_t m = members.size();
  std::vector<std::vector<char>> agree(m, std::vector<char>(m, 1));
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t j = i + 1; j < m; ++j) {
      agree[i][j] = agree[j][i] = Agree(graph.edges[static_cast<std::size_t>(members[i])],
                                        graph.edges[static_cast<std::size_t>(members[j])],
                                        poses, params);
    }
  }
  const auto count = [&](std::size_t i) { return std::count(agree[i].begin(), agree[i].end(), 1); };
  std::size_t seed = 0;
  for (std::size_t i = 1; i < m; ++i) {
    if (count(i) > count(seed)) seed = i;
  }
  std::vector<std::size_t> group;
  for (std::size_t i = 0; i < m; ++i) {
    if (agree[seed][i]) group.push_back(i);
  }
  while (true) {
    std::size_t worst = 0;
    long worst_count = 0;
    for (std::size_t g = 0; g < group.size(); ++g) {
      long against = 0;
      for (std::size_t h : group) against += agree[group[g]][h] ? 0 : 1;
      if (against > worst_count) worst = g, worst_count = against;
    }
    if (worst_count == 0) break;
    group.erase(group.begin() + static_cast<long>(worst));
  }
  std::vector<int> out;
  for (std::size_t g : group) out.push_back(members[g]);
  return out;
}

int CountAgreeing(const PoseGraph& graph, const std::vector<Pose2>& poses, double chi2) {
  int n = 0;
  for (const PoseGraphEdge& e : graph.edges) n += IsClosure(e) && ClosureAgrees(e, poses, chi2);
  return n;
}

}  // namespace

bool ClosureAgrees(const PoseGraphEdge& edge, const std::vector<Pose2>& poses, double chi2) {
  return EdgeChi2(edge, At(poses, edge.from), At(poses, edge.to)) <= chi2;
}

std::vector<std::vector<int>> ConsistentLoopGroups(const PoseGraph& graph,
                                                   const std::vector<Pose2>& poses,
                                                   const LoopGroupParams& params) {
  std::vector<int> disagreeing;
  for (int k = 0; k < static_cast<int>(graph.edges.size()); ++k) {
    const PoseGraphEdge& e = graph.edges[static_cast<std::size_t>(k)];
    if (IsClosure(e) && !ClosureAgrees(e, poses, params.agreement_chi2)) disagreeing.push_back(k);
  }
  std::stable_sort(disagreeing.begin(), disagreeing.end(), [&](int a, int b) {
    return graph.edges[static_cast<std::size_t>(a)].to < graph.edges[static_cast<std::size_t>(b)].to;
  });
  std::vector<std::vector<int>> groups;
  std::vector<int> cluster;
  const auto close_cluster = [&] {
    if (static_cast<int>(cluster.size()) >= params.min_size) {
      std::vector<int> group = AgreeingSubset(graph, poses, cluster, params);
      if (static_cast<int>(group.size()) >= params.min_size) groups.push_back(std::move(group));
    }
    cluster.clear();
  };
  for (const int k : disagreeing) {
    const int node = graph.edges[static_cast<std::size_t>(k)].to;
    if (!cluster.empty() &&
        node - graph.edges[static_cast<std::size_t>(cluster.back())].to >= params.max_node_gap) {
      close_cluster();
    }
    cluster.push_back(k);
  }
  close_cluster();
  std::stable_sort(groups.begin(), groups.end(),
                   [](const auto& a, const auto& b) { return a.size() > b.size(); });
  return groups;
}

PoseGraphSolution OptimizeWithLoopGroups(const PoseGraph& graph, const std::vector<Pose2>& initial,
                                         const PoseGraphOptimizerParams& params,
                                         const LoopGroupParams& groups, int first_new_edge) {
  PoseGraphSolution best = OptimizePoseGraph(graph, initial, params);
  if (groups.min_size <= 0) return best;
  double time_s = best.time_s;
  int agreeing = CountAgreeing(graph, best.poses, groups.agreement_chi2);
  PoseGraphOptimizerParams plain = params;
  plain.loop_closure_loss = RobustLossParams{.kind = RobustLossKind::kNone};
  std::vector<std::vector<int>> found = ConsistentLoopGroups(graph, best.poses, groups);
  std::size_t next = 0;
  for (int tried = 0; tried < groups.max_groups && next < found.size();) {
    const std::vector<int>& group = found[next];
    if (std::none_of(group.begin(), group.end(), [&](int k) { return k >= first_new_edge; })) {
      ++next;
      continue;
    }
    ++tried;
    PoseGraph pulled{graph.vertices, {}};
    for (const PoseGraphEdge& e : graph.edges) {
      if (!IsClosure(e)) pulled.edges.push_back(e);
    }
    for (const int k : group) pulled.edges.push_back(graph.edges[static_cast<std::size_t>(k)]);
    const PoseGraphSolution shut = OptimizePoseGraph(pulled, best.poses, plain);
    PoseGraphSolution whole = OptimizePoseGraph(graph, shut.poses, params);
    time_s += shut.time_s + whole.time_s;
    const int now = CountAgreeing(graph, whole.poses, groups.agreement_chi2);
    if (now <= agreeing) {
      ++next;
      continue;
    }
    best = std::move(whole);
    agreeing = now;
    found = ConsistentLoopGroups(graph, best.poses, groups);
    next = 0;
  }
  best.time_s = time_s;
  return best;
}

}  // namespace slamkit
