#include "slamkit/planning/grid_paths.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <utility>

namespace slamkit {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::array<std::array<int, 2>, 8> kSteps = {
    {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}}};

void CheckParams(const GridPathParams& p) {
  if (!(p.robot_radius_m >= 0.0 && p.clearance_m >= 0.0 && p.clearance_cost_weight >= 0.0) ||
      !(p.free_probability > 0.0 && p.free_probability <= p.occupied_probability &&
        p.occupied_probability < 1.0)) {
    throw std::invalid_argument(
        "grid paths: need radius, clearance, weight >= 0 and 0 < free <= occupied < 1");
  }
}

// A clearance is a rounded product (resolution × a distance in cells): one that is exactly the
// radius (the middle of a gap 2 × radius + one cell wide) may come out a rounding error below it,
// and must not block.
constexpr double kClearanceSlack_m = 1e-9;

// Whether a cell `clearance` from the nearest obstacle lies in the inflated zone.
bool Inflated(double clearance, const GridPathParams& p) {
  return clearance < p.robot_radius_m - kClearanceSlack_m;
}

// The penalty per metre of a cell `clearance` from the nearest obstacle (see GridPathParams).
double Penalty(double clearance, const GridPathParams& p) {
  if (Inflated(clearance, p)) return p.clearance_cost_weight;  // escaping an inflated zone
  if (p.clearance_m <= 0.0) return 0.0;
  const double excess = (clearance - p.robot_radius_m) / p.clearance_m;
  return p.clearance_cost_weight * std::clamp(1.0 - excess, 0.0, 1.0);
}

// An occupied cell all of whose 4-neighbours are occupied is never the nearest to a cell outside:
// the nearest point of the obstacles lies on a face they share with a non-occupied cell.
bool OnObstacleBorder(const std::vector<char>& occupied, int x, int y, int w, int h) {
  for (int k = 0; k < 4; ++k) {  // the first four steps are the 4-neighbours
    const int nx = x + kSteps[k][0], ny = y + kSteps[k][1];
    if (nx < 0 || ny < 0 || nx >= w || ny >= h || !occupied[std::size_t(ny) * w + nx]) return true;
  }
  return false;
}

}  // namespace

GridPathCosts GridPathCosts::From(const OccupancyGrid& grid, const Eigen::Vector2d& start_m,
                                  const GridPathParams& params) {
  CheckParams(params);
  GridPathCosts costs;
  costs.params_ = params;
  costs.resolution_m_ = grid.resolution();
  costs.start_ = grid.WorldToCell(start_m);
  // The written cells, the start (it may lie outside them before the first scan), and a ring of
  // one: the ring is unknown, so the search never leaves the window.
  CellIndex lo = costs.start_, hi = costs.start_;
  if (grid.min_cell().x <= grid.max_cell().x) {
    lo = {std::min(lo.x, grid.min_cell().x), std::min(lo.y, grid.min_cell().y)};
    hi = {std::max(hi.x, grid.max_cell().x), std::max(hi.y, grid.max_cell().y)};
  }
  costs.x0_ = lo.x - 1;
  costs.y0_ = lo.y - 1;
  costs.width_ = hi.x - lo.x + 3;
  costs.height_ = hi.y - lo.y + 3;
  costs.ComputeClearance(grid);
  costs.RunDijkstra();
  return costs;
}

// Each obstacle cell on a border stamps a disc of radius + clearance: the exact distance from a
// cell's centre to the nearest point of an occupied square, as far as the costs need it.
void GridPathCosts::ComputeClearance(const OccupancyGrid& grid) {
  const std::size_t n = static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
  free_.assign(n, 0);
  std::vector<char> occupied(n, 0);
  for (int y = y0_; y < y0_ + height_; ++y) {
    for (int x = x0_; x < x0_ + width_; ++x) {
      if (!grid.IsKnown({x, y})) continue;
      const double p = grid.Probability({x, y});
      free_[Index({x, y})] = p < params_.free_probability;
      occupied[Index({x, y})] = p > params_.occupied_probability;
    }
  }
  const double reach_m = params_.robot_radius_m + params_.clearance_m;
  const int reach = static_cast<int>(std::ceil(reach_m / resolution_m_)) + 1;
  struct Offset { int dx, dy; double d_m; };
  std::vector<Offset> disc;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      const double ex = std::max(std::abs(dx) - 0.5, 0.0), ey = std::max(std::abs(dy) - 0.5, 0.0);
      const double d = resolution_m_ * std::hypot(ex, ey);
      if (d < reach_m || (dx == 0 && dy == 0)) disc.push_back({dx, dy, d});
    }
  }
  clearance_m_.assign(n, kInf);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      if (!occupied[std::size_t(y) * width_ + x]) continue;
      clearance_m_[std::size_t(y) * width_ + x] = 0.0;  // inside an obstacle, no border stamps it
      if (!OnObstacleBorder(occupied, x, y, width_, height_)) continue;
      for (const Offset& o : disc) {
        const int nx = x + o.dx, ny = y + o.dy;
        if (nx < 0 || ny < 0 || nx >= width_ || ny >= height_) continue;
        double& c = clearance_m_[std::size_t(ny) * width_ + nx];
        c = std::min(c, o.d_m);
      }
    }
  }
}

// Dijkstra from the start. A step into a blocked free cell is allowed only farther from the
// obstacles than the cell it leaves: out of an inflated zone, never into or along one.
void GridPathCosts::RunDijkstra() {
  cost_m_.assign(clearance_m_.size(), kInf);
  parent_.assign(clearance_m_.size(), -1);
  using Entry = std::pair<double, CellIndex>;
  const auto later = [](const Entry& a, const Entry& b) { return a.first > b.first; };
  std::priority_queue<Entry, std::vector<Entry>, decltype(later)> open(later);
  cost_m_[Index(start_)] = 0.0;
  open.push({0.0, start_});
  while (!open.empty()) {
    const auto [cost, c] = open.top();
    open.pop();
    if (cost > cost_m_[Index(c)]) continue;  // a stale entry
    const double clear = clearance_m_[Index(c)];
    const double penalty = Penalty(clear, params_);
    for (int k = 0; k < 8; ++k) {
      const CellIndex next{c.x + kSteps[k][0], c.y + kSteps[k][1]};
      if (!Contains(next) || !free_[Index(next)]) continue;
      const double next_clear = clearance_m_[Index(next)];
      if (Inflated(next_clear, params_) && !(next_clear > clear)) continue;
      const double length = k < 4 ? resolution_m_ : resolution_m_ * std::sqrt(2.0);
      const double next_cost =
          cost + length * (1.0 + 0.5 * (penalty + Penalty(next_clear, params_)));
      if (next_cost < cost_m_[Index(next)]) {
        cost_m_[Index(next)] = next_cost;
        parent_[Index(next)] = static_cast<std::int8_t>(k);
        open.push({next_cost, next});
      }
    }
  }
}

bool GridPathCosts::Reachable(const CellIndex& c) const { return std::isfinite(Cost(c)); }

double GridPathCosts::Cost(const CellIndex& c) const {
  return Contains(c) ? cost_m_[Index(c)] : kInf;
}

std::vector<CellIndex> GridPathCosts::PathTo(const CellIndex& goal) const {
  if (!Reachable(goal)) return {};
  std::vector<CellIndex> path = {goal};
  while (!(path.back() == start_)) {
    const int k = parent_[Index(path.back())];
    path.push_back({path.back().x - kSteps[k][0], path.back().y - kSteps[k][1]});
  }
  std::reverse(path.begin(), path.end());
  return path;
}

double GridPathCosts::Clearance(const CellIndex& c) const {
  return Contains(c) ? clearance_m_[Index(c)] : kInf;
}

bool GridPathCosts::IsFree(const CellIndex& c) const { return Contains(c) && free_[Index(c)]; }

bool GridPathCosts::Traversable(const CellIndex& c) const {
  return IsFree(c) && !Inflated(Clearance(c), params_);
}

// Greedy line-of-sight: from the last waypoint, the path is followed as long as the straight line
// to its next cell keeps the clearance of the stretch it replaces (see the header).
std::vector<Eigen::Vector2d> SimplifyPath(const GridPathCosts& costs,
                                          const std::vector<CellIndex>& path,
                                          double max_segment_m) {
  if (path.empty()) return {};
  const double r = costs.params().robot_radius_m;
  const double needed_max = r + costs.params().clearance_m;
  const double res = costs.resolution();
  const auto centre = [res](const CellIndex& c) {
    return Eigen::Vector2d((c.x + 0.5) * res, (c.y + 0.5) * res);
  };
  const auto line_clear = [&](const CellIndex& a, const CellIndex& b, double needed) {
    const std::vector<CellIndex> cells = RayCells(a, b);
    return std::all_of(cells.begin() + 1, cells.end(), [&](const CellIndex& c) {
      return costs.IsFree(c) && costs.Clearance(c) >= needed - kClearanceSlack_m;
    });
  };
  std::vector<Eigen::Vector2d> waypoints = {centre(path.front())};
  std::size_t anchor = 0;
  double stretch_clearance = kInf;  // the least clearance of path(anchor, j]
  for (std::size_t j = 1; j < path.size(); ++j) {
    stretch_clearance = std::min(stretch_clearance, costs.Clearance(path[j]));
    if (j == anchor + 1) continue;  // a neighbour is always in sight
    const double needed = std::clamp(stretch_clearance, r, needed_max);
    const bool too_long = (centre(path[j]) - waypoints.back()).norm() > max_segment_m;
    if (too_long || !line_clear(path[anchor], path[j], needed)) {
      anchor = j - 1;
      waypoints.push_back(centre(path[anchor]));
      stretch_clearance = costs.Clearance(path[j]);
    }
  }
  if (path.size() > 1) waypoints.push_back(centre(path.back()));
  return waypoints;
}

std::optional<FrontierTarget> NearestReachableFrontier(const GridPathCosts& costs,
                                                       const std::vector<FrontierRegion>& regions,
                                                       const FrontierSkip& skip) {
  std::optional<FrontierTarget> best;
  for (int i = 0; i < static_cast<int>(regions.size()); ++i) {
    if (skip && skip(regions[i])) continue;
    for (const CellIndex& c : regions[i].cells) {
      const double cost = costs.Cost(c);
      if (std::isfinite(cost) && (!best || cost < best->cost_m)) best = {i, c, cost, {}};
    }
  }
  if (best) best->waypoints_m = SimplifyPath(costs, costs.PathTo(best->cell));
  return best;
}

// SPEC S4 step 1: the next exploration target.
std::optional<FrontierTarget> NearestReachableFrontier(const OccupancyGrid& grid,
                                                       const std::vector<FrontierRegion>& regions,
                                                       const Eigen::Vector2d& start_m,
                                                       const GridPathParams& params,
                                                       const FrontierSkip& skip) {
  return NearestReachableFrontier(GridPathCosts::From(grid, start_m, params), regions, skip);
}

}  // namespace slamkit
