#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"

namespace slamkit::testing {

// Wall segments of a 16 m × 10 m room with two pillars, so scans are not symmetric.
inline std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> RoomWalls() {
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> walls;
  auto box = [&](double x0, double y0, double x1, double y1) {
    walls.push_back({{x0, y0}, {x1, y0}});
    walls.push_back({{x1, y0}, {x1, y1}});
    walls.push_back({{x1, y1}, {x0, y1}});
    walls.push_back({{x0, y1}, {x0, y0}});
  };
  box(-8, -5, 8, 5);
  box(-3, 1, -2, 2.5);
  box(3, -2.5, 4.5, -1.5);
  return walls;
}

// Distance along the ray from `o` in direction `d` to the segment [a, b] (infinity if missed).
inline double RayToSegment(const Eigen::Vector2d& o, const Eigen::Vector2d& d,
                           const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  const double denom = d.x() * e.y() - d.y() * e.x();
  if (std::abs(denom) < 1e-12) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d w = a - o;
  const double t = (w.x() * e.y() - w.y() * e.x()) / denom;
  const double u = (w.x() * d.y() - w.y() * d.x()) / denom;
  if (t <= 0.0 || u < 0.0 || u > 1.0) return std::numeric_limits<double>::infinity();
  return t;
}

// A noise-free 180-beam scan (1° apart, -90°..89°) of the room from robot pose `pose`.
inline LaserScan RoomScan(const Pose2& pose, double t_s = 0.0, const Pose2& odometry = Pose2()) {
  LaserScan scan;
  scan.t_s = t_s;
  scan.odometry = odometry;
  scan.max_range_m = 30.0;
  const auto walls = RoomWalls();
  for (int i = 0; i < 180; ++i) {
    const double a = pose.theta() + scan.BeamAngle(i);
    const Eigen::Vector2d d(std::cos(a), std::sin(a));
    double r = scan.max_range_m;
    for (const auto& [p, q] : walls) r = std::min(r, RayToSegment(pose.translation(), d, p, q));
    scan.ranges_m.push_back(static_cast<float>(r));
  }
  return scan;
}

}  // namespace slamkit::testing
