#pragma once

#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"

namespace slamkit {

// Frontier points of one scan (SPEC S1, active SLAM loop; Tao et al. 2007): where the laser's
// free space reaches its range, the robot can go to see more.
struct FrontierParams {
  // A beam with no return, or one at or beyond this range, sees free space up to it: the
  // range the filter uses (the seed's 10 m), not necessarily the sensor's.
  double open_range_m = 10.0;
  // A frontier point lies on the middle beam of a run of open beams, this far from the laser
  // (at most open_range_m): far enough to see new space on arrival, short of the unknown.
  double goal_distance_m = 4.0;
  // The opening must be this wide for the robot to fit through: the returns on the run's two
  // sides this far apart, or (at an end of the scan) the run this wide at the goal distance.
  double min_width_m = 1.0;
  int min_beams = 3;  // fewer open beams are noise (a return lost on a dark surface)
};

struct Frontier {
  Eigen::Vector2d point_world_m;  // the frontier point
  double bearing_rad = 0.0;       // its direction from the robot, in the robot frame
  double width_m = 0.0;           // the opening's width (see FrontierParams::min_width_m)
  int first_beam = 0;             // the run of open beams, inclusive
  int last_beam = 0;
};

// SPEC S1, active loop, step 1: the frontier points of `scan` taken at `robot_pose` (the SLAM
// estimate: the points are in its world frame), in beam order.
std::vector<Frontier> FindFrontiers(const LaserScan& scan, const Pose2& robot_pose,
                                    const FrontierParams& params = {});

// How the next frontier is chosen among a scan's.
struct FrontierChoiceParams {
  // A frontier this close to a goal already reached (or to the start) leads back into explored
  // space and is not chosen.
  double revisit_radius_m = 2.0;
};

// SPEC S1, active loop, step 2: the frontier the robot turns least to face, among those not
// within revisit_radius_m of a visited point; none if every one is.
std::optional<Frontier> ChooseFrontier(std::span<const Frontier> frontiers,
                                       std::span<const Eigen::Vector2d> visited_m,
                                       const FrontierChoiceParams& params = {});

}  // namespace slamkit
