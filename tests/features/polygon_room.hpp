#pragma once

#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "common/synthetic_room.hpp"
#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/models/line_sensor.hpp"

namespace slamkit::testing {

using Wall = std::pair<Eigen::Vector2d, Eigen::Vector2d>;

// A room seen from the sensor at the origin, drawn in a frame turned by `phi_rad` about it (so the
// same geometry can put lines at any α, including near ±π). Unturned (phi = 0), the sensor faces
// +x and sees, in beam order:
//   0: wall y = −3 (x 0..6)    1: wall x = 6 (y −3..4)    2: wall y = 4 (x 6..≈4, up to the pillar)
//   3: pillar face y = 2.1     4: pillar face x = 1       5: wall y = 4 (x ≈1.3..0, behind it)
// with concave room corners (6, −3), (6, 4) and the pillar's convex corner (1, 2.1).
struct PolygonRoom {
  double phi_rad = 0.0;
  std::vector<Wall> walls;
  std::vector<PolarLine> visible_lines;  // in beam order, as listed above
  std::vector<Eigen::Vector2d> concave_corners;
  std::vector<Eigen::Vector2d> convex_corners;
};

inline PolygonRoom MakePolygonRoom(double phi_rad, bool door_in_front = false) {
  const Eigen::Rotation2Dd R(phi_rad);
  PolygonRoom room;
  room.phi_rad = phi_rad;
  auto add = [&](double x0, double y0, double x1, double y1) {
    room.walls.push_back({R * Eigen::Vector2d(x0, y0), R * Eigen::Vector2d(x1, y1)});
  };
  add(-1, -3, 6, -3);
  if (door_in_front) {  // a 1 m door in x = 6 with nothing behind it within range
    add(6, -3, 6, -0.5);
    add(6, 0.5, 6, 4);
  } else {
    add(6, -3, 6, 4);
  }
  add(6, 4, -1, 4);
  add(-1, 4, -1, -3);
  add(1, 2.1, 2, 2.1);  // the pillar [1, 2] × [2.1, 3.1]
  add(2, 2.1, 2, 3.1);
  add(2, 3.1, 1, 3.1);
  add(1, 3.1, 1, 2.1);
  const double half_pi = std::numbers::pi / 2.0;
  const std::vector<std::pair<double, double>> lines = {
      {3.0, -half_pi}, {6.0, 0.0}, {4.0, half_pi}, {2.1, half_pi}, {1.0, 0.0}, {4.0, half_pi}};
  for (const auto& [rho, alpha] : lines) {
    room.visible_lines.push_back({rho, WrapLineAngle(alpha + phi_rad)});
  }
  room.concave_corners = {R * Eigen::Vector2d(6, -3), R * Eigen::Vector2d(6, 4)};
  room.convex_corners = {R * Eigen::Vector2d(1, 2.1)};
  return room;
}

// A SICK-like scan of `room`: 181 beams, 1° apart, over the 180° in front of the (turned) sensor,
// `max_range_m` for beams that hit nothing. Each beam is cast at its angle plus N(0, σ_φ) and its
// range gets N(0, σ_r), as a real laser's bearing and range errors would.
inline LaserScan ScanPolygonRoom(const PolygonRoom& room, Rng* rng = nullptr,
                                 double sigma_range_m = 0.0, double sigma_bearing_rad = 0.0,
                                 double max_range_m = 30.0) {
  LaserScan scan;
  scan.angle_min_rad = -std::numbers::pi / 2.0 + room.phi_rad;
  scan.angle_increment_rad = std::numbers::pi / 180.0;
  scan.max_range_m = max_range_m;
  for (int i = 0; i < 181; ++i) {
    const double a = scan.BeamAngle(i) + (rng ? rng->Normal(0.0, sigma_bearing_rad) : 0.0);
    const Eigen::Vector2d d(std::cos(a), std::sin(a));
    double r = max_range_m;
    for (const auto& [p, q] : room.walls) {
      r = std::min(r, RayToSegment(Eigen::Vector2d::Zero(), d, p, q));
    }
    if (r < max_range_m && rng) r += rng->Normal(0.0, sigma_range_m);
    scan.ranges_m.push_back(static_cast<float>(r));
  }
  return scan;
}

}  // namespace slamkit::testing
