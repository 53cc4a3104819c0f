// A route that drives every corridor of SPEC S4's square maze, so that a simulated run maps all of
// it (the maze experiment's full coverage run).

#include "slamkit/sim/maze_route.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace slamkit {
namespace {

// Waypoints of a serpentine over the crossings of the corridor centre lines; `At(i, j)` is the
// crossing of column i and row j.
class SerpentineBuilder {
 public:
  SerpentineBuilder(const std::vector<double>& centres, const Eigen::Vector2d& origin)
      : centres_(centres), origin_(origin), last_(static_cast<int>(centres.size()) - 1) {}

  std::vector<Eigen::Vector2d> Build() {
    // Rows: start each row where the previous one ended (one corridor north) and drive it to the
    // other end.
    for (int j = 0; j <= last_; ++j) {
      GoTo(column_, j);
      column_ = last_ - column_;
      GoTo(column_, j);
    }
    // Columns, starting with the one the rows ended in, from the top row: each one driven to the
    // other end, then along the top or bottom row to the next column.
    int row = last_;
    const int step = column_ == 0 ? 1 : -1;
    for (int i = column_; i >= 0 && i <= last_; i += step) {
      GoTo(i, row);
      row = last_ - row;
      GoTo(i, row);
    }
    // Back along the outer ring: the closing leg to waypoint 0 must follow a corridor.
    if (row != 0 && current_column_ != 0) GoTo(0, row);
    if (waypoints_.size() > 1 && waypoints_.back() == waypoints_.front()) waypoints_.pop_back();
    return waypoints_;
  }

 private:
  void GoTo(int i, int j) {
    const Eigen::Vector2d p = origin_ + Eigen::Vector2d(centres_[i], centres_[j]);
    if (waypoints_.empty() || waypoints_.back() != p) waypoints_.push_back(p);
    current_column_ = i;
  }

  const std::vector<double>& centres_;
  Eigen::Vector2d origin_;
  int last_;
  int column_ = 0;          // where the row serpentine is
  int current_column_ = 0;  // column of the last waypoint
  std::vector<Eigen::Vector2d> waypoints_;
};

}  // namespace

std::vector<double> SquareMazeCorridorCentres(const SquareMazeParams& params) {
  const double outer = params.outer_size_m;
  const double block = params.block_size_m;
  const double corridor = params.corridor_width_m;
  if (!(outer > 0.0 && block > 0.0 && corridor > 0.0) || !std::isfinite(outer + block + corridor)) {
    throw std::invalid_argument("SquareMazeCorridorCentres: sizes must be positive and finite");
  }
  // The block count and outer corridor width exactly as MakeSquareMaze lays them out.
  const double pitch = block + corridor;
  const int n = std::max(0, static_cast<int>(std::floor((outer - corridor) / pitch + 1e-9)));
  if (n == 0) return {};
  const double margin = 0.5 * (outer - n * block - (n - 1) * corridor);
  std::vector<double> centres = {0.5 * margin};
  for (int k = 1; k < n; ++k) centres.push_back(margin + k * pitch - 0.5 * corridor);
  centres.push_back(outer - 0.5 * margin);
  return centres;
}

RouteParams MazeRoute(const SquareMazeParams& params, int loops, double switch_distance_m) {
  const std::vector<double> centres = SquareMazeCorridorCentres(params);
  if (centres.empty()) throw std::invalid_argument("MazeRoute: the maze has no block");
  if (!params.origin_m.allFinite()) throw std::invalid_argument("MazeRoute: origin not finite");
  RouteParams route;
  route.waypoints_m = SerpentineBuilder(centres, params.origin_m).Build();
  route.loops = loops;
  route.switch_distance_m = switch_distance_m;
  return route;
}

Pose2 RouteStartPose(const RouteParams& route) {
  if (route.waypoints_m.size() < 2) {
    throw std::invalid_argument("RouteStartPose: a route needs at least 2 waypoints");
  }
  const Eigen::Vector2d& from = route.waypoints_m[0];
  const Eigen::Vector2d heading = route.waypoints_m[1] - from;
  return Pose2(from.x(), from.y(), std::atan2(heading.y(), heading.x()));
}

}  // namespace slamkit
