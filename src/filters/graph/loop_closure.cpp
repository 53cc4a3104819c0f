#include "slamkit/filters/graph/loop_closure.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>

#include <tbb/parallel_for.h>

namespace slamkit {

Eigen::Matrix3d DiagonalInformation(double sigma_xy_m, double sigma_theta_rad) {
  return Eigen::Vector3d(1.0 / (sigma_xy_m * sigma_xy_m), 1.0 / (sigma_xy_m * sigma_xy_m),
                         1.0 / (sigma_theta_rad * sigma_theta_rad))
      .asDiagonal();
}

PoseGraphEdge LoopClosureEdge(const LoopClosure& closure, const LoopClosureParams& params) {
  const Eigen::Matrix3d full = DiagonalInformation(params.sigma_xy_m, params.sigma_theta_rad);
  if (closure.keep.isIdentity()) return {closure.anchor_node, closure.node, closure.relative, full};
  constexpr double kUnconstrained = 1e-4;  // information, so σ 100 times the closure's
  const Eigen::Matrix3d info =
      closure.keep.transpose() * full * closure.keep + kUnconstrained * full;
  return {closure.anchor_node, closure.node, closure.relative, 0.5 * (info + info.transpose())};
}

CorrelativeWindow LoopWindow(const LoopClosureParams& p, double driven_m) {
  return {std::min(p.max_linear_window_m, p.base_linear_window_m + p.linear_window_growth * driven_m),
          std::min(p.max_angular_window_rad,
                   p.base_angular_window_rad + p.angular_window_growth_rad_per_m * driven_m)};
}

bool SubmapWithinReach(const Submap& submap, const Pose2& node_in_local,
                       const CorrelativeWindow& window, const LoopClosureParams& params) {
  const double reach = window.linear_m * M_SQRT2 + params.max_node_distance_m;
  const Eigen::Vector2d at = node_in_local.translation();
  return std::any_of(submap.poses.begin(), submap.poses.end(),
                     [&](const Pose2& p) { return (p.translation() - at).norm() <= reach; });
}

namespace {

// The submap's node nearest to `at` (local frame). A closure is tied to it rather than to the
// submap's first node: the map where the scan matched is that node's scans and its neighbours',
// placed by the front end relative to it, while the first node may be a hundred nodes of
// front-end drift away.
std::size_t NearestNode(const Submap& submap, const Eigen::Vector2d& at) {
  std::size_t nearest = 0;
  for (std::size_t k = 1; k < submap.poses.size(); ++k) {
    if ((submap.poses[k].translation() - at).squaredNorm() <
        (submap.poses[nearest].translation() - at).squaredNorm()) {
      nearest = k;
    }
  }
  return nearest;
}

}  // namespace

// Hess et al. 2016, Section V: branch and bound over the window, then a fine match from its
// result (their Ceres refinement; here the hill climb of the front end).
std::optional<LoopClosure> MatchLoopClosure(int node, const Submap& submap,
                                            const CorrelativeMatcher& matcher,
                                            const ScanPoints& points, const Pose2& node_in_local,
                                            const CorrelativeWindow& window,
                                            const LoopClosureParams& params) {
  const std::optional<CorrelativeMatch> coarse =
      matcher.BranchAndBound(points.ends, node_in_local, window);
  if (!coarse) return std::nullopt;
  const MatchResult fine = MatchScan(submap.grid, points, coarse->pose, params.refinement);
  if (!fine.accepted) return std::nullopt;
  const std::size_t anchor = NearestNode(submap, fine.pose.translation());
  return LoopClosure{node, submap.index, submap.nodes[anchor],
                     submap.poses[anchor].Between(fine.pose), coarse->score,
                     fine.constraints.keep};
}

}  // namespace slamkit

namespace slamkit {
namespace {

struct LoopPair {
  int input_index;  // into LoopSearchInput::nodes
  Pose2 node_in_local;
  CorrelativeWindow window;
};

}  // namespace

std::vector<double> DriftDistances(const LoopSearchInput& in) {
  const int n = static_cast<int>(in.submaps.size());
  std::vector<double> dist(static_cast<std::size_t>(n), std::numeric_limits<double>::infinity());
  if (in.nodes.empty() || n == 0) return dist;
  const double now = in.driven_m[static_cast<std::size_t>(in.nodes.front())];
  // The adjacency: chain neighbours, and submaps joined through a closure's node.
  std::vector<std::vector<std::pair<int, double>>> next(static_cast<std::size_t>(n));
  std::vector<int> position(in.submaps.empty() ? 0 : in.submaps.back()->index + 1, -1);
  for (int k = 0; k < n; ++k) position[static_cast<std::size_t>(in.submaps[k]->index)] = k;
  const auto origin_driven = [&](int k) {
    return in.driven_m[static_cast<std::size_t>(in.submaps[k]->origin_node)];
  };
  for (int k = 0; k + 1 < n; ++k) {
    const double w = std::abs(origin_driven(k + 1) - origin_driven(k));
    next[k].push_back({k + 1, w});
    next[k + 1].push_back({k, w});
  }
  const int size = static_cast<int>(position.size());
  for (const LoopClosure& c : in.closures) {
    const int a = c.submap < size ? position[static_cast<std::size_t>(c.submap)] : -1;
    for (const int t : {c.node / in.nodes_per_submap - 1, c.node / in.nodes_per_submap}) {
      const int b = t >= 0 && t < size ? position[static_cast<std::size_t>(t)] : -1;
      if (a < 0 || b < 0 || a == b) continue;
      next[a].push_back({b, 0.0});
      next[b].push_back({a, 0.0});
    }
  }
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  for (int k = 0; k < n; ++k) {
    const double last = in.driven_m[static_cast<std::size_t>(in.submaps[k]->nodes.back())];
    dist[k] = std::max(0.0, now - last);
    open.push({dist[k], k});
  }
  while (!open.empty()) {
    const auto [d, k] = open.top();
    open.pop();
    if (d > dist[k]) continue;
    for (const auto& [m, w] : next[k]) {
      if (d + w < dist[m]) open.push({dist[m] = d + w, m});
    }
  }
  return dist;
}

std::vector<LoopClosure> SearchLoopClosures(const LoopSearchInput& in,
                                            const LoopClosureParams& params) {
  const std::vector<double> drift = DriftDistances(in);
  const double now = in.nodes.empty() ? 0.0 : in.driven_m[static_cast<std::size_t>(in.nodes.front())];
  std::vector<std::vector<LoopPair>> pairs(in.submaps.size());
  for (std::size_t k = 0; k < in.submaps.size(); ++k) {
    const Submap& s = *in.submaps[k];
    const Pose2 origin_global = in.global[static_cast<std::size_t>(s.origin_node)];
    for (std::size_t i = 0; i < in.nodes.size(); ++i) {
      const int node = in.nodes[i];
      if (node <= s.nodes.back()) continue;  // in the submap, or before it ended
      const double driven = drift[k] + in.driven_m[static_cast<std::size_t>(node)] - now;
      const CorrelativeWindow window = LoopWindow(params, driven);
      if (params.thin_wide_windows && params.base_linear_window_m > 0.0) {
        const int every = std::max(1, static_cast<int>(window.linear_m / params.base_linear_window_m));
        if ((node / params.node_stride) % every != 0) continue;
      }
      const Pose2 local =
          s.origin.Compose(origin_global.Between(in.global[static_cast<std::size_t>(node)]));
      if (SubmapWithinReach(s, local, window, params)) {
        pairs[k].push_back({static_cast<int>(i), local, window});
      }
    }
  }
  std::vector<std::vector<LoopClosure>> found(in.submaps.size());
  tbb::parallel_for(std::size_t{0}, in.submaps.size(), [&](std::size_t k) {
    if (pairs[k].empty()) return;
    const Submap& s = *in.submaps[k];
    const CorrelativeMatcher matcher(s.grid, params.matcher);
    for (const LoopPair& p : pairs[k]) {
      const std::size_t i = static_cast<std::size_t>(p.input_index);
      if (auto c = MatchLoopClosure(in.nodes[i], s, matcher, *in.points[i], p.node_in_local,
                                    p.window, params)) {
        found[k].push_back(*c);
      }
    }
  });
  std::vector<LoopClosure> out;
  for (const auto& f : found) out.insert(out.end(), f.begin(), f.end());
  std::stable_sort(out.begin(), out.end(), [](const LoopClosure& a, const LoopClosure& b) {
    return a.node != b.node ? a.node < b.node : a.submap < b.submap;
  });
  return out;
}

}  // namespace slamkit
