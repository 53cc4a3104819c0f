#include "slamkit/filters/graph/correlative_matcher.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace slamkit {
namespace {

void CheckParams(const CorrelativeMatcherParams& p) {
  if (!(p.linear_window_m >= 0.0 && p.angular_window_rad >= 0.0 && p.angular_step_rad >= 0.0) ||
      p.branch_and_bound_depth < 1 || p.branch_and_bound_depth > 16 ||
      !(p.min_score >= 0.0 && p.min_score <= 1.0)) {
    throw std::invalid_argument(
        "correlative matcher: windows and step must be >= 0, depth in [1, 16], min_score in "
        "[0, 1]");
  }
}

}  // namespace

// Level 0 holds each cell's occupancy (unknown: 0); level h each cell's max over the 2^h × 2^h
// cells from it, built from level h − 1 (Hess et al. Section V.C). Every level spans the map's
// cells and 2^(depth−1) − 1 more below and left, where a coarse candidate's cells may start.
CorrelativeMatcher::CorrelativeMatcher(const OccupancyGrid& map,
                                       const CorrelativeMatcherParams& params)
    : params_(params), resolution_m_(map.resolution()) {
  CheckParams(params);
  const int margin = (1 << (params.branch_and_bound_depth - 1)) - 1;
  const bool empty = map.min_cell().x > map.max_cell().x;
  x0_ = (empty ? 0 : map.min_cell().x) - margin;
  y0_ = (empty ? 0 : map.min_cell().y) - margin;
  width_ = empty ? 1 : map.max_cell().x - map.min_cell().x + 1 + margin;
  height_ = empty ? 1 : map.max_cell().y - map.min_cell().y + 1 + margin;
  levels_.resize(static_cast<std::size_t>(params.branch_and_bound_depth));
  const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  levels_[0].value.assign(n, 0);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const CellIndex c{x0_ + x, y0_ + y};
      if (map.IsKnown(c)) {
        levels_[0].value[std::size_t(y) * width_ + x] =
            static_cast<std::uint16_t>(std::lround(map.Probability(c) * kProbabilitySteps));
      }
    }
  }
  for (std::size_t h = 1; h < levels_.size(); ++h) {
    const int s = 1 << (h - 1);
    const std::vector<std::uint16_t>& below = levels_[h - 1].value;
    const auto at = [&](int x, int y) -> std::uint16_t {
      return x < width_ && y < height_ ? below[std::size_t(y) * width_ + x] : 0;
    };
    levels_[h].value.resize(n);
    for (int y = 0; y < height_; ++y) {
      for (int x = 0; x < width_; ++x) {
        levels_[h].value[std::size_t(y) * width_ + x] =
            std::max({at(x, y), at(x + s, y), at(x, y + s), at(x + s, y + s)});
      }
    }
  }
}

CorrelativeMatcher::Query CorrelativeMatcher::MakeQuery(
    const std::vector<Eigen::Vector2d>& points, const Pose2& initial,
    const std::optional<CorrelativeWindow>& window) const {
  const CorrelativeWindow w =
      window.value_or(CorrelativeWindow{params_.linear_window_m, params_.angular_window_rad});
  if (!(w.linear_m >= 0.0 && w.angular_rad >= 0.0 && std::isfinite(w.linear_m) &&
        std::isfinite(w.angular_rad))) {
    throw std::invalid_argument("correlative matcher: a window must be finite and >= 0");
  }
  Query q;
  q.window_cells = static_cast<int>(std::ceil(w.linear_m / resolution_m_));
  double reach = 0.0;
  for (const Eigen::Vector2d& p : points) reach = std::max(reach, p.norm());
  double step = params_.angular_step_rad;
  if (step <= 0.0) {
    const double r = resolution_m_;
    step = reach > r ? std::acos(1.0 - r * r / (2.0 * reach * reach)) : w.angular_rad;
  }
  const int n = step > 0.0 ? static_cast<int>(std::ceil(w.angular_rad / step)) : 0;
  for (int k = -n; k <= n; ++k) {
    Rotated r;
    r.theta = initial.theta() + k * step;
    const Pose2 pose(initial.x(), initial.y(), r.theta);
    for (const Eigen::Vector2d& p : points) {
      const Eigen::Vector2d c = pose.TransformFrom(p) / resolution_m_;
      r.cells.emplace_back(static_cast<int>(std::floor(c.x())), static_cast<int>(std::floor(c.y())));
    }
    q.rotations.push_back(std::move(r));
  }
  return q;
}

double CorrelativeMatcher::Score(Query& q, int rotation, int dx, int dy, int level) const {
  ++q.scored;
  const std::vector<std::uint16_t>& grid = levels_[static_cast<std::size_t>(level)].value;
  const Rotated& r = q.rotations[static_cast<std::size_t>(rotation)];
  std::uint64_t sum = 0;
  for (const Eigen::Vector2i& c : r.cells) {
    const int x = c.x() + dx - x0_, y = c.y() + dy - y0_;
    if (x >= 0 && y >= 0 && x < width_ && y < height_) sum += grid[std::size_t(y) * width_ + x];
  }
  return static_cast<double>(sum) / (static_cast<double>(r.cells.size()) * kProbabilitySteps);
}

std::optional<CorrelativeMatch> CorrelativeMatcher::Result(const Query& q, const Candidate& best,
                                                           const Pose2& initial,
                                                           long* scored) const {
  if (scored) *scored = q.scored;
  if (best.rotation < 0) return std::nullopt;
  return CorrelativeMatch{Pose2(initial.x() + best.dx * resolution_m_,
                                initial.y() + best.dy * resolution_m_,
                                q.rotations[static_cast<std::size_t>(best.rotation)].theta),
                          best.score};
}

std::optional<CorrelativeMatch> CorrelativeMatcher::Exhaustive(
    const std::vector<Eigen::Vector2d>& points, const Pose2& initial,
    const std::optional<CorrelativeWindow>& window, long* scored) const {
  if (points.empty()) return std::nullopt;
  Query q = MakeQuery(points, initial, window);
  const int w = q.window_cells;
  Candidate best{-1, 0, 0, 0, params_.min_score};
  bool found = false;
  for (int k = 0; k < static_cast<int>(q.rotations.size()); ++k) {
    for (int dx = -w; dx <= w; ++dx) {
      for (int dy = -w; dy <= w; ++dy) {
        const double s = Score(q, k, dx, dy, 0);
        if (s > best.score || (!found && s >= best.score)) {
          best = {k, dx, dy, 0, s};
          found = true;
        }
      }
    }
  }
  return Result(q, best, initial, scored);
}

// Depth first, the best child first; a candidate whose bound cannot beat the best is dropped
// with everything below it (the bound: a level-h cell is the max of the cells it covers).
void CorrelativeMatcher::Search(Query& q, const Candidate& c, Candidate* best) const {
  if (c.score <= best->score && best->rotation >= 0) return;
  if (c.score < best->score) return;
  if (c.level == 0) {
    *best = c;
    return;
  }
  const int s = 1 << (c.level - 1);
  std::vector<Candidate> children;
  for (const int ox : {0, s}) {
    for (const int oy : {0, s}) {
      const int dx = c.dx + ox, dy = c.dy + oy;
      if (dx > q.window_cells || dy > q.window_cells) continue;
      children.push_back({c.rotation, dx, dy, c.level - 1, Score(q, c.rotation, dx, dy, c.level - 1)});
    }
  }
  std::sort(children.begin(), children.end(),
            [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  for (const Candidate& child : children) Search(q, child, best);
}

std::optional<CorrelativeMatch> CorrelativeMatcher::BranchAndBound(
    const std::vector<Eigen::Vector2d>& points, const Pose2& initial,
    const std::optional<CorrelativeWindow>& window, long* scored) const {
  if (points.empty()) return std::nullopt;
  Query q = MakeQuery(points, initial, window);
  const int top = params_.branch_and_bound_depth - 1, step = 1 << top, w = q.window_cells;
  std::vector<Candidate> candidates;
  for (int k = 0; k < static_cast<int>(q.rotations.size()); ++k) {
    for (int dx = -w; dx <= w; dx += step) {
      for (int dy = -w; dy <= w; dy += step) {
        candidates.push_back({k, dx, dy, top, Score(q, k, dx, dy, top)});
      }
    }
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.score > b.score; });
  Candidate best{-1, 0, 0, 0, params_.min_score};
  for (const Candidate& c : candidates) Search(q, c, &best);
  return Result(q, best, initial, scored);
}

}  // namespace slamkit
