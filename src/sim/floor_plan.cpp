// Wall plans for the grid-world laser simulator, and a ray caster that stays fast on plans of
// thousands of walls: the walls are bucketed into a uniform grid of square cells and a ray visits
// only the cells it crosses, in order (an Amanatides–Woo DDA walk), stopping at the first cell
// whose far boundary lies beyond the nearest hit found so far.

#include "slamkit/sim/floor_plan.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace slamkit {
namespace {

constexpr double kNoHit = std::numeric_limits<double>::infinity();
// Below this many walls, testing every wall beats walking the grid.
constexpr std::size_t kMinWallsForGrid = 64;
constexpr double kCellSize_m = 1.0;
constexpr double kMaxCells = 1 << 20;  // larger plans get larger cells
// A ray through a wall's end point hits it even when rounding puts the crossing a hair outside.
constexpr double kEndSlack = 1e-9;
// A wall is filed in every cell it passes within this distance of, so that a crossing on a cell
// boundary or corner is found from whichever side the ray arrives.
constexpr double kTouch_m = 1e-6;

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Distance t > 0 along the ray o + t·d to the closed segment [a, b], or kNoHit. Solves
// o + t·d = a + u·(b − a) with 2D cross products.
double RayToWall(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const Eigen::Vector2d& a,
                 const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  const Eigen::Vector2d w = a - o;
  const double denom = Cross(d, e);
  // A wall seen edge-on shows the ray no surface, and dividing by ~0 would give garbage.
  if (std::abs(denom) <= 1e-12 * (std::abs(e.x()) + std::abs(e.y()))) return kNoHit;
  const double t = Cross(w, e) / denom;
  const double u = Cross(w, d) / denom;
  if (!(t > 0.0) || u < -kEndSlack || u > 1.0 + kEndSlack) return kNoHit;
  return t;
}

// One axis of the DDA walk: which way the cell index moves, the ray distance at which it next
// changes, and the ray distance between changes.
struct Axis {
  int step = 0;
  double t_next = kNoHit;
  double t_delta = kNoHit;
};

Axis StartAxis(double origin, double direction, double grid_min, int index, double cell_m) {
  if (direction > 0.0) {
    return {1, (grid_min + (index + 1) * cell_m - origin) / direction, cell_m / direction};
  }
  if (direction < 0.0) {
    return {-1, (grid_min + index * cell_m - origin) / direction, -cell_m / direction};
  }
  return {};
}

void AddBox(const Eigen::Vector2d& lo, const Eigen::Vector2d& hi, std::vector<WallSegment>* walls) {
  const Eigen::Vector2d lo_hi(lo.x(), hi.y());
  const Eigen::Vector2d hi_lo(hi.x(), lo.y());
  walls->push_back({lo, hi_lo});
  walls->push_back({hi_lo, hi});
  walls->push_back({hi, lo_hi});
  walls->push_back({lo_hi, lo});
}

// Calls emit(begin, end) for each maximal run [begin, end) of k in [0, n) with is_edge(k).
template <typename IsEdge, typename Emit>
void ForEachRun(int n, IsEdge is_edge, Emit emit) {
  for (int k = 0; k < n;) {
    if (!is_edge(k)) {
      ++k;
      continue;
    }
    const int begin = k;
    while (k < n && is_edge(k)) ++k;
    emit(begin, k);
  }
}

}  // namespace

// The walls, each copied into every cell it touches (compressed rows: the walls of cell c are
// cell_walls_[cell_start_[c] .. cell_start_[c + 1])), so a cell's walls lie together in memory.
class WallGrid {
 public:
  explicit WallGrid(const std::vector<WallSegment>& walls);
  double Cast(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_range_m) const;

 private:
  int CellX(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - min_m_.x()) / cell_m_)), 0, nx_ - 1);
  }
  int CellY(double y) const {
    return std::clamp(static_cast<int>(std::floor((y - min_m_.y()) / cell_m_)), 0, ny_ - 1);
  }
  template <typename Visit>
  void ForEachTouchedCell(const WallSegment& wall, Visit visit) const;
  bool ClipToBounds(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double* t_enter,
                    double* t_leave) const;

  Eigen::Vector2d min_m_ = Eigen::Vector2d::Zero();
  double cell_m_ = kCellSize_m;
  int nx_ = 1;
  int ny_ = 1;
  std::vector<int> cell_start_;
  std::vector<WallSegment> cell_walls_;
};

WallGrid::WallGrid(const std::vector<WallSegment>& walls) {
  Eigen::Vector2d lo = walls.empty() ? Eigen::Vector2d::Zero() : walls[0].first;
  Eigen::Vector2d hi = lo;
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const auto& [a, b] = walls[i];
    if (!a.allFinite() || !b.allFinite()) {
      throw std::invalid_argument("FloorPlan: wall " + std::to_string(i) + " is not finite");
    }
    lo = lo.cwiseMin(a).cwiseMin(b);
    hi = hi.cwiseMax(a).cwiseMax(b);
  }
  const Eigen::Vector2d extent = hi - lo;
  cell_m_ = std::max({kCellSize_m, std::sqrt(extent.x() * extent.y() / kMaxCells),
                      extent.maxCoeff() / std::sqrt(kMaxCells)});
  min_m_ = lo;
  nx_ = static_cast<int>(std::floor(extent.x() / cell_m_)) + 1;
  ny_ = static_cast<int>(std::floor(extent.y() / cell_m_)) + 1;
  // Two passes: count each cell's walls, then copy them into place.
  cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (const WallSegment& wall : walls) {
    ForEachTouchedCell(wall, [&](int c) { ++cell_start_[c + 1]; });
  }
  std::partial_sum(cell_start_.begin(), cell_start_.end(), cell_start_.begin());
  cell_walls_.resize(cell_start_.back());
  std::vector<int> next(cell_start_.begin(), cell_start_.end() - 1);
  for (const WallSegment& wall : walls) {
    ForEachTouchedCell(wall, [&](int c) { cell_walls_[next[c]++] = wall; });
  }
}

// Cells of the wall's bounding box that the wall's line passes through (a separating-axis test
// along the wall's normal), boxes and line both grown by kTouch_m.
template <typename Visit>
void WallGrid::ForEachTouchedCell(const WallSegment& wall, Visit visit) const {
  const auto& [a, b] = wall;
  const Eigen::Vector2d normal(a.y() - b.y(), b.x() - a.x());
  const double reach = (0.5 * cell_m_ + kTouch_m) * (std::abs(normal.x()) + std::abs(normal.y()));
  const int x_end = CellX(std::max(a.x(), b.x()) + kTouch_m);
  const int y_end = CellY(std::max(a.y(), b.y()) + kTouch_m);
  for (int iy = CellY(std::min(a.y(), b.y()) - kTouch_m); iy <= y_end; ++iy) {
    for (int ix = CellX(std::min(a.x(), b.x()) - kTouch_m); ix <= x_end; ++ix) {
      const Eigen::Vector2d centre = min_m_ + cell_m_ * Eigen::Vector2d(ix + 0.5, iy + 0.5);
      if (std::abs(normal.dot(centre - a)) <= reach) visit(iy * nx_ + ix);
    }
  }
}

// Narrows [t_enter, t_leave] to the part of the ray inside the grid (slab method); false when
// nothing of it is left.
bool WallGrid::ClipToBounds(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double* t_enter,
                            double* t_leave) const {
  if (!o.allFinite() || !d.allFinite()) return false;
  const Eigen::Vector2d max_m = min_m_ + cell_m_ * Eigen::Vector2d(nx_, ny_);
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (o[k] < min_m_[k] || o[k] > max_m[k]) return false;
      continue;
    }
    const double t0 = (min_m_[k] - o[k]) / d[k];
    const double t1 = (max_m[k] - o[k]) / d[k];
    *t_enter = std::max(*t_enter, std::min(t0, t1));
    *t_leave = std::min(*t_leave, std::max(t0, t1));
  }
  return *t_enter <= *t_leave;
}

double WallGrid::Cast(const Eigen::Vector2d& o, const Eigen::Vector2d& d,
                      double max_range_m) const {
  double t_enter = 0.0;
  double t_end = max_range_m;
  if (!ClipToBounds(o, d, &t_enter, &t_end)) return max_range_m;
  const Eigen::Vector2d start = o + t_enter * d;
  int ix = CellX(start.x());
  int iy = CellY(start.y());
  Axis x = StartAxis(o.x(), d.x(), min_m_.x(), ix, cell_m_);
  Axis y = StartAxis(o.y(), d.y(), min_m_.y(), iy, cell_m_);
  double best = max_range_m;
  while (true) {
    const int cell = iy * nx_ + ix;
    for (int k = cell_start_[cell]; k < cell_start_[cell + 1]; ++k) {
      best = std::min(best, RayToWall(o, d, cell_walls_[k].first, cell_walls_[k].second));
    }
    // Every wall crossed before the ray leaves this cell is filed in a cell already visited.
    const double t_leave = std::min(x.t_next, y.t_next);
    if (best <= t_leave || t_leave >= t_end) return best;
    const bool along_x = x.t_next < y.t_next;
    Axis& axis = along_x ? x : y;
    int& index = along_x ? ix : iy;
    index += axis.step;
    axis.t_next += axis.t_delta;
    if (ix < 0 || ix >= nx_ || iy < 0 || iy >= ny_) return best;
  }
}

WallIndexCache& WallIndexCache::operator=(const WallIndexCache& /*other*/) {
  Reset();
  return *this;
}

std::shared_ptr<const WallGrid> WallIndexCache::Get(const std::vector<WallSegment>& walls) const {
  const std::lock_guard lock(mutex_);
  if (!grid_ || built_from_data_ != walls.data() || built_from_size_ != walls.size()) {
    grid_ = std::make_shared<const WallGrid>(walls);
    built_from_data_ = walls.data();
    built_from_size_ = walls.size();
  }
  return grid_;
}

void WallIndexCache::Reset() {
  const std::lock_guard lock(mutex_);
  grid_.reset();
  built_from_data_ = nullptr;
  built_from_size_ = 0;
}

RayCaster::RayCaster(const FloorPlan& plan) : plan_(&plan) {
  if (plan.walls.size() >= kMinWallsForGrid) grid_ = plan.ray_index.Get(plan.walls);
}

double RayCaster::Cast(const Eigen::Vector2d& origin_m, const Eigen::Vector2d& unit_direction,
                       double max_range_m) const {
  if (grid_) return grid_->Cast(origin_m, unit_direction, max_range_m);
  return CastRayBruteForce(*plan_, origin_m, unit_direction, max_range_m);
}

double CastRay(const FloorPlan& plan, const Eigen::Vector2d& origin_m,
               const Eigen::Vector2d& unit_direction, double max_range_m) {
  return RayCaster(plan).Cast(origin_m, unit_direction, max_range_m);
}

double CastRayBruteForce(const FloorPlan& plan, const Eigen::Vector2d& origin_m,
                         const Eigen::Vector2d& unit_direction, double max_range_m) {
  double best = max_range_m;
  for (const auto& [a, b] : plan.walls) {
    best = std::min(best, RayToWall(origin_m, unit_direction, a, b));
  }
  return best;
}

FloorPlan MakeSquareMaze(const SquareMazeParams& params) {
  const double outer = params.outer_size_m;
  const double block = params.block_size_m;
  const double corridor = params.corridor_width_m;
  if (!(outer > 0.0 && block > 0.0 && corridor > 0.0) || !std::isfinite(outer + block + corridor) ||
      !params.origin_m.allFinite()) {
    throw std::invalid_argument("MakeSquareMaze: sizes must be positive and finite");
  }
  FloorPlan plan;
  const Eigen::Vector2d& origin = params.origin_m;
  AddBox(origin, origin + Eigen::Vector2d(outer, outer), &plan.walls);
  // n blocks need n + 1 corridors; the slack 1e-9 keeps an exact fit (the default) from rounding
  // down to one block fewer.
  const double pitch = block + corridor;
  const int n = std::max(0, static_cast<int>(std::floor((outer - corridor) / pitch + 1e-9)));
  const double margin = 0.5 * (outer - n * block - (n - 1) * corridor);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d lo = origin + Eigen::Vector2d(margin + i * pitch, margin + j * pitch);
      AddBox(lo, lo + Eigen::Vector2d(block, block), &plan.walls);
    }
  }
  return plan;
}

FloorPlan FloorPlanFromOccupancy(const OccupancyImage& image, std::uint8_t occupied_below) {
  const int w = image.width;
  const int h = image.height;
  if (w < 0 || h < 0 || image.pixels.size() != static_cast<std::size_t>(w) * h) {
    throw std::invalid_argument("FloorPlanFromOccupancy: pixel count is not width × height");
  }
  if (!(image.resolution_m > 0.0) || !std::isfinite(image.resolution_m) ||
      !image.origin_m.allFinite()) {
    throw std::invalid_argument("FloorPlanFromOccupancy: bad resolution or origin");
  }
  // Column c, row r counted from the bottom; outside the image is free.
  auto occupied = [&](int c, int r) {
    if (c < 0 || c >= w || r < 0 || r >= h) return false;
    return image.pixels[static_cast<std::size_t>(h - 1 - r) * w + c] < occupied_below;
  };
  auto corner = [&](int c, int r) {
    return Eigen::Vector2d(image.origin_m + image.resolution_m * Eigen::Vector2d(c, r));
  };
  FloorPlan plan;
  for (int r = 0; r <= h; ++r) {  // horizontal pixel edges on the line between rows r − 1 and r
    ForEachRun(w, [&](int c) { return occupied(c, r - 1) != occupied(c, r); },
               [&](int c0, int c1) { plan.walls.push_back({corner(c0, r), corner(c1, r)}); });
  }
  for (int c = 0; c <= w; ++c) {  // vertical pixel edges on the line between columns c − 1 and c
    ForEachRun(h, [&](int r) { return occupied(c - 1, r) != occupied(c, r); },
               [&](int r0, int r1) { plan.walls.push_back({corner(c, r0), corner(c, r1)}); });
  }
  return plan;
}

}  // namespace slamkit
