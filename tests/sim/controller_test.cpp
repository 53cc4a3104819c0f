#include "slamkit/sim/controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

RouteParams Square(double side_m, int loops, double switch_m) {
  RouteParams route;
  route.waypoints_m = {{0.0, 0.0}, {side_m, 0.0}, {side_m, side_m}, {0.0, side_m}};
  route.loops = loops;
  route.switch_distance_m = switch_m;
  return route;
}

struct Drive {
  std::vector<int> targets;       // the waypoint index after each change
  std::vector<double> closest_m;  // per waypoint, the closest the robot came
  Pose2 final_pose;
  int steps = 0;
  bool done = false;
};

// Drives the noise-free vehicle with the controller until it is done or `max_steps` pass, and
// checks the command limits at every step.
Drive DriveRoute(const RouteParams& route, const ControllerParams& params, MotionKind kind,
                 double dt_s, int max_steps) {
  VehicleParams vehicle;  // an odometry robot drives as a unicycle (see Simulate)
  vehicle.kind = kind == MotionKind::kOdometry ? MotionKind::kUnicycle : kind;
  const auto model = MakeMotionModel(vehicle);
  WaypointController controller(route, params, kind);
  Drive drive;
  drive.closest_m.assign(route.waypoints_m.size(), 1e9);
  Pose2 pose(0.0, 0.0, 0.0);
  double previous_steer = 0.0;
  for (; drive.steps < max_steps; ++drive.steps) {
    const Control u = controller.Command(pose, dt_s);
    if (controller.Done()) break;
    if (drive.targets.empty() || drive.targets.back() != controller.CurrentWaypoint()) {
      drive.targets.push_back(controller.CurrentWaypoint());
    }
    EXPECT_DOUBLE_EQ(u[0], params.speed_mps);
    if (kind == MotionKind::kCarLike) {
      EXPECT_LE(std::abs(u[1]), params.max_steer_rad + 1e-12);
      EXPECT_LE(std::abs(u[1] - previous_steer), params.max_steer_rate_radps * dt_s + 1e-12);
      previous_steer = u[1];
    } else {
      EXPECT_LE(std::abs(u[1]), params.max_turn_rate_radps + 1e-12);
    }
    pose = model->Move(pose, u, dt_s);
    for (std::size_t w = 0; w < route.waypoints_m.size(); ++w) {
      const double d = (route.waypoints_m[w] - pose.translation()).norm();
      drive.closest_m[w] = std::min(drive.closest_m[w], d);
    }
  }
  drive.done = controller.Done();
  drive.final_pose = pose;
  return drive;
}

void ExpectRouteDriven(const Drive& drive, const RouteParams& route, std::vector<int> targets) {
  EXPECT_TRUE(drive.done);
  EXPECT_EQ(drive.targets, targets);
  for (double d : drive.closest_m) EXPECT_LE(d, route.switch_distance_m);
  EXPECT_LE((drive.final_pose.translation() - route.waypoints_m[0]).norm(),
            route.switch_distance_m);
}

TEST(WaypointController, UnicycleDrivesSquareInOrderAndFinishes) {
  const RouteParams route = Square(20.0, 1, 1.0);
  ControllerParams params;
  params.speed_mps = 1.0;
  const Drive drive = DriveRoute(route, params, MotionKind::kUnicycle, 0.1, 5000);
  ExpectRouteDriven(drive, route, {1, 2, 3, 0});
  // 80 m at 1 m/s: about 800 steps of 0.1 s, a little less for the cut corners.
  EXPECT_GT(drive.steps, 700);
  EXPECT_LT(drive.steps, 850);
}

TEST(WaypointController, CarLikeDrivesSquareTwiceInOrderAndFinishes) {
  const RouteParams route = Square(40.0, 2, 2.0);
  const ControllerParams params;  // 3 m/s, 30° steering, 20°/s
  const Drive drive = DriveRoute(route, params, MotionKind::kCarLike, 0.025, 20000);
  ExpectRouteDriven(drive, route, {1, 2, 3, 0, 1, 2, 3, 0});
  EXPECT_LT(drive.steps, 2 * 160 / (3.0 * 0.025) * 1.1);
}

TEST(WaypointController, OdometryKindSteersLikeUnicycle) {
  const RouteParams route = Square(10.0, 1, 0.5);
  ControllerParams params;
  params.speed_mps = 0.5;
  params.max_turn_rate_radps = 0.5;
  const Drive drive = DriveRoute(route, params, MotionKind::kOdometry, 0.1, 5000);
  ExpectRouteDriven(drive, route, {1, 2, 3, 0});
}

TEST(WaypointController, StartsAwayFromTheRouteAndStopsWhenDone) {
  RouteParams route = Square(10.0, 1, 0.5);
  for (Eigen::Vector2d& w : route.waypoints_m) w += Eigen::Vector2d(5.0, 5.0);
  ControllerParams params;
  params.speed_mps = 1.0;
  const Drive drive = DriveRoute(route, params, MotionKind::kUnicycle, 0.1, 5000);
  // Reaching waypoint 0 the first time does not end the run: the full loop follows.
  ExpectRouteDriven(drive, route, {0, 1, 2, 3, 0});

  WaypointController controller(route, params, MotionKind::kUnicycle);
  const Control u = controller.Command(Pose2(5.0, 5.0, 0.0), 0.1);
  EXPECT_EQ(controller.CurrentWaypoint(), 1);
  EXPECT_GT(u[0], 0.0);
}

TEST(WaypointController, ProportionalTurnRateBelowTheLimit) {
  RouteParams route;
  route.waypoints_m = {{0.0, 0.0}, {10.0, 1.0}};
  ControllerParams params;
  params.heading_gain_per_s = 2.0;
  params.max_turn_rate_radps = 1.0;
  WaypointController controller(route, params, MotionKind::kUnicycle);
  const Control u = controller.Command(Pose2(0.0, 0.0, 0.0), 0.1);
  EXPECT_EQ(controller.CurrentWaypoint(), 1);
  EXPECT_NEAR(u[1], 2.0 * std::atan2(1.0, 10.0), 1e-12);
  const Control v = controller.Command(Pose2(0.0, 0.0, -2.0), 0.1);
  EXPECT_DOUBLE_EQ(v[1], 1.0);
}

TEST(WaypointController, CarLikeSteeringRateLimited) {
  RouteParams route;
  route.waypoints_m = {{0.0, 0.0}, {0.0, 10.0}};  // 90° to the left
  const ControllerParams params;
  WaypointController controller(route, params, MotionKind::kCarLike);
  const double dt = 0.1;
  const double rate_step = params.max_steer_rate_radps * dt;
  EXPECT_NEAR(controller.Command(Pose2(0.0, 0.0, 0.0), dt)[1], rate_step, 1e-12);
  EXPECT_NEAR(controller.Command(Pose2(0.0, 0.0, 0.0), dt)[1], 2.0 * rate_step, 1e-12);
  for (int i = 0; i < 100; ++i) controller.Command(Pose2(0.0, 0.0, 0.0), dt);
  EXPECT_NEAR(controller.Command(Pose2(0.0, 0.0, 0.0), dt)[1], params.max_steer_rad, 1e-12);
}

TEST(WaypointController, DetourIsDrivenToThenTheRouteResumesAtItsWaypoint) {
  // Square of 40 m; on the way to waypoint 1 (40, 0) the car is sent to (20, 25), passing
  // near waypoint 3 (0, 40)'s side of the square but not reaching any waypoint meanwhile.
  const RouteParams route = Square(40.0, 1, 2.0);
  const ControllerParams params;
  const auto model = MakeMotionModel(VehicleParams{});  // car-like
  WaypointController controller(route, params, MotionKind::kCarLike);
  Pose2 pose(0.0, 0.0, 0.0);
  const Eigen::Vector2d detour(20.0, 25.0);
  double closest_to_detour = 1e9;
  int waypoint_when_reached = -1;
  for (int k = 0; k < 4000 && !controller.Done(); ++k) {
    if (k == 40) {
      ASSERT_EQ(controller.CurrentWaypoint(), 1);
      controller.SetDetour(detour);
    }
    const Control u = controller.Command(pose, 0.025);
    if (k > 40 && waypoint_when_reached < 0 && !controller.Detour()) {
      waypoint_when_reached = controller.CurrentWaypoint();
    }
    pose = model->Move(pose, u, 0.025);
    closest_to_detour = std::min(closest_to_detour, (pose.translation() - detour).norm());
    if (k > 40 && controller.Detour()) {
      EXPECT_EQ(controller.CurrentWaypoint(), 1);
    }
  }
  EXPECT_LE(closest_to_detour, route.switch_distance_m);
  EXPECT_EQ(waypoint_when_reached, 1);  // resumed at the waypoint it had left
  EXPECT_TRUE(controller.Done());
}

TEST(WaypointController, AbandonedDetourResumesTheRoute) {
  WaypointController controller(Square(40.0, 1, 2.0), ControllerParams{}, MotionKind::kUnicycle);
  controller.Command(Pose2(0.0, 0.0, 0.0), 0.025);
  controller.SetDetour(Eigen::Vector2d(0.0, -30.0));
  const Control to_detour = controller.Command(Pose2(5.0, 0.0, 0.0), 0.025);
  EXPECT_LT(to_detour[1], 0.0);  // turning right, toward the detour
  controller.SetDetour(std::nullopt);
  const Control to_route = controller.Command(Pose2(5.0, 0.0, 0.0), 0.025);
  EXPECT_DOUBLE_EQ(to_route[1], 0.0);  // straight on to (40, 0)
  EXPECT_EQ(controller.CurrentWaypoint(), 1);
}

}  // namespace
}  // namespace slamkit
