#include "slamkit/planning/frontiers.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

enum class Beam { kOpen, kReturn, kInvalid };

Beam Classify(const LaserScan& scan, int i, double open_range_m) {
  const float r = scan.ranges_m[i];
  if (!std::isfinite(r) || r <= 0.0f) return Beam::kInvalid;  // says nothing either way
  if (!scan.IsReturn(i) || r >= open_range_m) return Beam::kOpen;
  return Beam::kReturn;
}

// Beam i's end point at `range` in the robot frame.
Eigen::Vector2d RobotPoint(const LaserScan& scan, int i, double range) {
  const double a = scan.BeamAngle(i);
  return scan.laser_offset.TransformFrom(range * Eigen::Vector2d(std::cos(a), std::sin(a)));
}

// The opening of the run [first, last] of open beams: the gap between the returns on its two
// sides when both are returns (a door is as wide as its frame, however few beams pass through
// it from afar), else its chord at the goal distance.
double OpeningWidth(const LaserScan& scan, int first, int last, const FrontierParams& params) {
  const int n = static_cast<int>(scan.ranges_m.size());
  if (first > 0 && last + 1 < n &&
      Classify(scan, first - 1, params.open_range_m) == Beam::kReturn &&
      Classify(scan, last + 1, params.open_range_m) == Beam::kReturn) {
    const Eigen::Vector2d a = RobotPoint(scan, first - 1, scan.ranges_m[first - 1]);
    const Eigen::Vector2d b = RobotPoint(scan, last + 1, scan.ranges_m[last + 1]);
    return (a - b).norm();
  }
  const double span = std::abs((last - first) * scan.angle_increment_rad);
  return 2.0 * params.goal_distance_m * std::sin(std::min(span, M_PI) / 2.0);
}

}  // namespace

// SPEC S1, active loop (Tao et al. 2007): runs of open beams wide enough for the robot.
std::vector<Frontier> FindFrontiers(const LaserScan& scan, const Pose2& robot_pose,
                                    const FrontierParams& params) {
  std::vector<Frontier> frontiers;
  const int n = static_cast<int>(scan.ranges_m.size());
  const double distance = std::min(params.goal_distance_m, params.open_range_m);
  for (int first = 0; first < n;) {
    if (Classify(scan, first, params.open_range_m) != Beam::kOpen) {
      ++first;
      continue;
    }
    int last = first;
    while (last + 1 < n && Classify(scan, last + 1, params.open_range_m) == Beam::kOpen) ++last;
    const double width = OpeningWidth(scan, first, last, params);
    if (last - first + 1 >= params.min_beams && width >= params.min_width_m) {
      const Eigen::Vector2d point_robot = RobotPoint(scan, (first + last) / 2, distance);
      frontiers.push_back({.point_world_m = robot_pose.TransformFrom(point_robot),
                           .bearing_rad = std::atan2(point_robot.y(), point_robot.x()),
                           .width_m = width,
                           .first_beam = first,
                           .last_beam = last});
    }
    first = last + 1;
  }
  return frontiers;
}

std::optional<Frontier> ChooseFrontier(std::span<const Frontier> frontiers,
                                       std::span<const Eigen::Vector2d> visited_m,
                                       const FrontierChoiceParams& params) {
  std::optional<Frontier> best;
  for (const Frontier& f : frontiers) {
    const bool revisits = std::any_of(visited_m.begin(), visited_m.end(), [&](const auto& v) {
      return (f.point_world_m - v).norm() < params.revisit_radius_m;
    });
    if (revisits) continue;
    if (!best || std::abs(f.bearing_rad) < std::abs(best->bearing_rad)) best = f;
  }
  return best;
}

}  // namespace slamkit
