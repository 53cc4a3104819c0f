// Occupancy-grid SLAM (a Rao-Blackwellised particle filter) on data made up here: a robot drives
// a circle in an empty 10 m x 10 m room, and we give the filter its noisy odometry and the laser
// scans it would see, computed by intersecting each beam with the four walls.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/grid/rbpf_grid_slam.hpp"

using namespace slamkit;

constexpr double kHalfRoom = 5.0;  // walls at x = ±5 m and y = ±5 m

// Distance from `from` along heading `angle` to the first wall of the room (the robot is inside).
double RangeToWalls(const Eigen::Vector2d& from, double angle) {
  const double dx = std::cos(angle), dy = std::sin(angle);
  double range = std::numeric_limits<double>::infinity();
  if (dx > 1e-12) range = std::min(range, (kHalfRoom - from.x()) / dx);
  if (dx < -1e-12) range = std::min(range, (-kHalfRoom - from.x()) / dx);
  if (dy > 1e-12) range = std::min(range, (kHalfRoom - from.y()) / dy);
  if (dy < -1e-12) range = std::min(range, (-kHalfRoom - from.y()) / dy);
  return range;
}

int main() {
  RbpfGridSlamParams params;  // defaults as `slamkit grid`, with fewer particles and updates
  params.particles = 10;      // more often (every 0.5 m or 0.25 rad of odometry)
  params.linear_update_m = 0.5;
  params.angular_update_rad = 0.25;
  RbpfGridSlam filter(params);

  Rng rng(7);
  const double dt = 0.1, v = 0.5, w = 0.25;  // a circle of radius 2 m, one lap in ~25 s
  const Pose2 start(2.0, 0.0, M_PI / 2);
  Pose2 truth = start;
  Pose2 odometry;  // what the wheels report: starts at 0 and drifts from the truth
  for (int step = 0; step <= 252; ++step) {
    if (step > 0) {
      // One step of true motion, and the same step as odometry measures it (with noise).
      const Pose2 delta(v * dt, 0.0, w * dt);
      truth = truth.Compose(delta);
      odometry = odometry.Compose(Pose2(delta.x() + rng.Normal(0, 0.005),
                                        rng.Normal(0, 0.002), delta.theta() + rng.Normal(0, 0.003)));
    }
    // A 180° scan with 1° between beams, 1 cm range noise; the laser sits at the robot's centre.
    LaserScan scan;
    scan.t_s = step * dt;
    scan.angle_min_rad = -M_PI / 2;
    scan.angle_increment_rad = M_PI / 180;
    scan.max_range_m = 20.0;
    scan.odometry = odometry;
    for (int i = 0; i < 181; ++i) {
      const double r = RangeToWalls(truth.translation(), truth.theta() + scan.BeamAngle(i));
      scan.ranges_m.push_back(static_cast<float>(r + rng.Normal(0, 0.01)));
    }
    filter.ProcessScan(scan);
  }

  // The filter's frame has the start pose at the origin: compare with the truth seen from there.
  const Pose2 est = filter.CurrentPose();
  const Pose2 true_rel = start.Between(truth);
  std::printf("true pose:  x=%.3f y=%.3f theta=%.3f (from the start)\n", true_rel.x(),
              true_rel.y(), true_rel.theta());
  std::printf("final pose: x=%.3f y=%.3f theta=%.3f after %d updates\n", est.x(), est.y(),
              est.theta(), filter.updates());

  // The best particle's map: its extent, and the cells it believes occupied (the walls).
  const OccupancyGrid& map = filter.BestMap();
  const CellIndex lo = map.min_cell(), hi = map.max_cell();
  int occupied = 0;
  for (int y = lo.y; y <= hi.y; ++y)
    for (int x = lo.x; x <= hi.x; ++x) occupied += map.LogOdds({x, y}) > 0.0f;
  std::printf("map: %.2f m x %.2f m, %d occupied cells of %.2f m\n",
              (hi.x - lo.x + 1) * map.resolution(), (hi.y - lo.y + 1) * map.resolution(), occupied,
              map.resolution());
  return 0;
}
