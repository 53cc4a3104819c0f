#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <stdexcept>
#include <utility>

#include "slamkit/planning/grid_paths.hpp"

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

// Whether a cell `clearance` from the nearest obstacle lies in the inflated zone.
bool Inflated(double clearance, const GridPathParams& p) {
  return clearance < p.robot_radius_m - GridPathCosts::kClearanceSlack_m;
}

// The penalty per metre of a cell `clearance` from the nearest obstacle (see GridPathParams).
double Penalty(double clearance, const GridPathParams& p) {
  if (Inflated(clearance, p)) return p.clearance_cost_weight;  // escaping an inflated zone
  if (p.clearance_m <= 0.0) return 0.0;
  const double excess = (clearance - p.robot_radius_m) / p.clearance_m;
  return p.clearance_cost_weight * std::clamp(1.0 - excess, 0.0, 1.0);
}

}  // namespace

GridPathCosts::GridPathCosts(const OccupancyGrid& grid, const Eigen::Vector2d& start_m,
                             const GridPathParams& params)
    : grid_(grid), params_(params), resolution_m_(grid.resolution()),
      start_(grid.WorldToCell(start_m)) {
  CheckParams(params);
  // The written cells, the start (it may lie outside them before the first scan), and a ring of
  // one: the ring is unknown, so the search never leaves the window.
  CellIndex lo = start_, hi = start_;
  if (grid.min_cell().x <= grid.max_cell().x) {
    lo = {std::min(lo.x, grid.min_cell().x), std::min(lo.y, grid.min_cell().y)};
    hi = {std::max(hi.x, grid.max_cell().x), std::max(hi.y, grid.max_cell().y)};
  }
  x0_ = lo.x - 1;
  y0_ = lo.y - 1;
  width_ = hi.x - lo.x + 3;
  height_ = hi.y - lo.y + 3;
  tiles_x_ = (width_ + kTileSize - 1) / kTileSize;
  tiles_.resize(static_cast<std::size_t>(tiles_x_) * ((height_ + kTileSize - 1) / kTileSize));
  // The distance from a cell's centre to the nearest point of the square `(dx, dy)` cells away.
  const double reach_m = params_.robot_radius_m + params_.clearance_m;
  reach_cells_ = static_cast<int>(std::ceil(reach_m / resolution_m_)) + 1;
  for (int dy = -reach_cells_; dy <= reach_cells_; ++dy) {
    for (int dx = -reach_cells_; dx <= reach_cells_; ++dx) {
      const double ex = std::max(std::abs(dx) - 0.5, 0.0), ey = std::max(std::abs(dy) - 0.5, 0.0);
      const double d = resolution_m_ * std::hypot(ex, ey);
      if (d < reach_m || (dx == 0 && dy == 0)) disc_.push_back({dx, dy, d});
    }
  }
  std::stable_sort(disc_.begin(), disc_.end(),
                   [](const DiscOffset& a, const DiscOffset& b) { return a.d_m < b.d_m; });
}

GridPathCosts GridPathCosts::From(const OccupancyGrid& grid, const Eigen::Vector2d& start_m,
                                  const GridPathParams& params) {
  GridPathCosts costs(grid, start_m, params);
  costs.RunDijkstra({});
  return costs;
}

GridPathCosts GridPathCosts::UpToNearestGoal(const OccupancyGrid& grid,
                                             const Eigen::Vector2d& start_m,
                                             const std::function<bool(const CellIndex&)>& is_goal,
                                             const GridPathParams& params) {
  GridPathCosts costs(grid, start_m, params);
  costs.RunDijkstra(is_goal);
  return costs;
}

bool GridPathCosts::ReadFree(const CellIndex& c) const {
  return Contains(c) && grid_.IsKnown(c) && grid_.Probability(c) < params_.free_probability;
}

bool GridPathCosts::ReadOccupied(const CellIndex& c) const {
  return Contains(c) && grid_.IsKnown(c) && grid_.Probability(c) > params_.occupied_probability;
}

// An occupied cell all of whose 4-neighbours are occupied is never the nearest to a cell outside:
// the nearest point of the obstacles lies on a face they share with a non-occupied cell.
bool GridPathCosts::OnObstacleBorder(const CellIndex& c) const {
  for (int k = 0; k < 4; ++k) {  // the first four steps are the 4-neighbours
    if (!ReadOccupied({c.x + kSteps[k][0], c.y + kSteps[k][1]})) return true;
  }
  return false;
}

const GridPathCosts::Tile* GridPathCosts::FindTile(const CellIndex& c) const {
  return Contains(c) ? tiles_[TileIndex(c)].get() : nullptr;
}

GridPathCosts::Tile& GridPathCosts::PreparedTile(const CellIndex& c) {
  std::shared_ptr<Tile>& slot = tiles_[TileIndex(c)];
  if (slot) return *slot;
  slot = std::make_shared<Tile>();
  const CellIndex origin{x0_ + ((c.x - x0_) & ~(kTileSize - 1)),
                         y0_ + ((c.y - y0_) & ~(kTileSize - 1))};
  for (int y = 0; y < kTileSize; ++y) {
    for (int x = 0; x < kTileSize; ++x) {
      slot->free[y * kTileSize + x] = ReadFree({origin.x + x, origin.y + y});
    }
  }
  slot->cost_m.fill(kInf);
  slot->parent.fill(-1);
  PrepareClearance(origin, *slot);
  return *slot;
}

// Each obstacle cell on a border within reach stamps its disc onto the tile: the exact distance
// from a cell's centre to the nearest point of an occupied square, as far as the costs need it.
void GridPathCosts::PrepareClearance(const CellIndex& origin, Tile& tile) const {
  tile.clearance_m.fill(kInf);
  const int reach = reach_cells_;
  for (int y = origin.y - reach; y < origin.y + kTileSize + reach; ++y) {
    for (int x = origin.x - reach; x < origin.x + kTileSize + reach; ++x) {
      if (!ReadOccupied({x, y})) continue;
      const bool inside = x >= origin.x && y >= origin.y && x < origin.x + kTileSize &&
                          y < origin.y + kTileSize;
      if (inside) tile.clearance_m[InTile({x, y}, origin)] = 0.0;  // no border stamps it
      if (!OnObstacleBorder({x, y})) continue;
      for (const DiscOffset& o : disc_) {
        const int nx = x + o.dx - origin.x, ny = y + o.dy - origin.y;
        if (nx < 0 || ny < 0 || nx >= kTileSize || ny >= kTileSize) continue;
        double& cl = tile.clearance_m[ny * kTileSize + nx];
        cl = std::min(cl, o.d_m);
      }
    }
  }
}

double GridPathCosts::ReadClearance(const CellIndex& c) const {
  if (ReadOccupied(c)) return 0.0;
  for (const DiscOffset& o : disc_) {  // nearest first: the first border cell found is the nearest
    const CellIndex b{c.x - o.dx, c.y - o.dy};
    if (ReadOccupied(b) && OnObstacleBorder(b)) return o.d_m;
  }
  return kInf;
}

// Dijkstra from the start. A step into a blocked free cell is allowed only farther from the
// obstacles than the cell it leaves: out of an inflated zone, never into or along one. With
// is_goal, it stops when the queue holds nothing as cheap as the first goal settled.
void GridPathCosts::RunDijkstra(const std::function<bool(const CellIndex&)>& is_goal) {
  using Entry = std::pair<double, CellIndex>;
  const auto later = [](const Entry& a, const Entry& b) { return a.first > b.first; };
  std::priority_queue<Entry, std::vector<Entry>, decltype(later)> open(later);
  if (!Contains(start_)) return;
  PreparedTile(start_).cost_m[InTile(start_)] = 0.0;
  open.push({0.0, start_});
  double goal_cost = kInf;
  while (!open.empty() && open.top().first <= goal_cost) {
    const auto [cost, c] = open.top();
    open.pop();
    Tile& here = PreparedTile(c);
    if (cost > here.cost_m[InTile(c)]) continue;  // a stale entry
    if (is_goal && !goal_ && is_goal(c)) {
      goal_ = c;
      goal_cost = cost;
    }
    const double clear = here.clearance_m[InTile(c)];
    const double penalty = Penalty(clear, params_);
    for (int k = 0; k < 8; ++k) {
      const CellIndex next{c.x + kSteps[k][0], c.y + kSteps[k][1]};
      if (!Contains(next)) continue;
      Tile& there = PreparedTile(next);
      const int i = InTile(next);
      if (!there.free[i]) continue;
      const double next_clear = there.clearance_m[i];
      if (Inflated(next_clear, params_) && !(next_clear > clear)) continue;
      const double length = k < 4 ? resolution_m_ : resolution_m_ * std::sqrt(2.0);
      const double next_cost =
          cost + length * (1.0 + 0.5 * (penalty + Penalty(next_clear, params_)));
      if (next_cost < there.cost_m[i]) {
        there.cost_m[i] = next_cost;
        there.parent[i] = static_cast<std::int8_t>(k);
        open.push({next_cost, next});
      }
    }
  }
}

bool GridPathCosts::Reachable(const CellIndex& c) const { return std::isfinite(Cost(c)); }

double GridPathCosts::Cost(const CellIndex& c) const {
  const Tile* tile = FindTile(c);
  return tile ? tile->cost_m[InTile(c)] : kInf;
}

std::vector<CellIndex> GridPathCosts::PathTo(const CellIndex& goal) const {
  if (!Reachable(goal)) return {};
  std::vector<CellIndex> path = {goal};
  while (!(path.back() == start_)) {
    const int k = FindTile(path.back())->parent[InTile(path.back())];
    path.push_back({path.back().x - kSteps[k][0], path.back().y - kSteps[k][1]});
  }
  std::reverse(path.begin(), path.end());
  return path;
}

double GridPathCosts::Clearance(const CellIndex& c) const {
  if (!Contains(c)) return kInf;
  const Tile* tile = FindTile(c);
  return tile ? tile->clearance_m[InTile(c)] : ReadClearance(c);
}

bool GridPathCosts::IsFree(const CellIndex& c) const {
  const Tile* tile = FindTile(c);
  return tile ? tile->free[InTile(c)] != 0 : ReadFree(c);
}

bool GridPathCosts::Traversable(const CellIndex& c) const {
  return IsFree(c) && !Inflated(Clearance(c), params_);
}

}  // namespace slamkit
