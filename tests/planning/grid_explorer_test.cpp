#include "slamkit/planning/grid_explorer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "slamkit/core/rng.hpp"
#include "slamkit/sim/floor_plan.hpp"
#include "slamkit/sim/laser_sim.hpp"

namespace slamkit::grid_explorer_test {
namespace {

constexpr double kDt = 0.1;  // the control period

// The unicycle integrated exactly over one period (an arc of a circle, or a straight line).
Pose2 Drive(const Pose2& x, const Control& u) {
  const double v = u(0), w = u(1), th = x.theta();
  if (std::abs(w) < 1e-12) {
    return Pose2(x.x() + v * kDt * std::cos(th), x.y() + v * kDt * std::sin(th), th);
  }
  return Pose2(x.x() + v / w * (std::sin(th + w * kDt) - std::sin(th)),
               x.y() - v / w * (std::cos(th + w * kDt) - std::cos(th)), th + w * kDt);
}

double SegmentDistance(const Eigen::Vector2d& p, const WallSegment& w) {
  const Eigen::Vector2d d = w.second - w.first;
  const double s = std::clamp((p - w.first).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (w.first + s * d)).norm();
}

double WallDistance(const FloorPlan& plan, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const WallSegment& w : plan.walls) best = std::min(best, SegmentDistance(p, w));
  return best;
}

void AddBox(double x0, double y0, double x1, double y1, FloorPlan* plan) {
  const Eigen::Vector2d a(x0, y0), b(x1, y0), c(x1, y1), d(x0, y1);
  plan->walls.insert(plan->walls.end(), {{a, b}, {b, c}, {c, d}, {d, a}});
}

// Two rooms of 3.5 × 3.5 m side by side, joined by a 1 m door (2 < y < 3) in the wall between.
// A partition at y = 1.75 from that wall to x = 5.5 hides the lower part of the second room from
// the door and the first room: the robot has to go in and round it. Inner walls are 0.1 m thick:
// a wall of no thickness is invisible edge-on, and a robot on its line would erase it from the map.
FloorPlan TwoRooms() {
  FloorPlan plan;
  AddBox(0.0, 0.0, 7.0, 3.5, &plan);
  AddBox(3.45, 0.0, 3.55, 2.0, &plan);
  AddBox(3.45, 3.0, 3.55, 3.5, &plan);
  AddBox(3.55, 1.7, 5.5, 1.8, &plan);
  return plan;
}

// A noise-free scan from the true pose, inserted into the map.
void Sense(const FloorPlan& plan, const Pose2& x, OccupancyGrid* map, Rng& rng) {
  LaserSimParams laser = SpecS1Laser();
  laser.sigma_range_m = 0.0;
  const LaserScan scan = SimulateScan(plan, x, laser, rng);
  InsertScan(*map, x.Compose(scan.laser_offset), scan);
}

using FreeSpace = std::function<bool(const Eigen::Vector2d&)>;

// The share of the plan's free area (`free_space` inside [0, w] × [0, h], more than two cells
// from any wall) that the map knows as free.
double Coverage(const FloorPlan& plan, const FreeSpace& free_space, const OccupancyGrid& map,
                double w, double h, double free_probability) {
  const double res = map.resolution();
  int area = 0, known = 0;
  for (int y = 0; (y + 0.5) * res < h; ++y) {
    for (int x = 0; (x + 0.5) * res < w; ++x) {
      const Eigen::Vector2d p = map.CellCenter({x, y});
      if (!free_space(p) || WallDistance(plan, p) <= 2.0 * res) continue;
      ++area;
      known += map.IsKnown({x, y}) && map.Probability({x, y}) < free_probability;
    }
  }
  return static_cast<double>(known) / area;
}

// The closed loop, driven by the true pose: sense, plan, move, until done or out of steps.
struct Exploration {
  bool done = false;
  int steps = 0;
  int turning_steps = 0;  // periods spent in the start turn
  int targets = 0;
  double closest_m = std::numeric_limits<double>::infinity();  // to the plan's walls
  double max_v = 0.0, min_v = 0.0, max_abs_w = 0.0;
  Control last = Control::Zero(2);
  double coverage = 0.0;
};

Exploration Explore(const FloorPlan& plan, const FreeSpace& free_space, Pose2 x, double width_m,
                    double height_m, int max_steps, double resolution_m = 0.05) {
  const GridExplorerParams params;
  GridExplorer explorer(params);
  OccupancyGrid map(OccupancyGridParams{resolution_m});
  Rng rng(5);
  Exploration e;
  for (; e.steps < max_steps && !explorer.done(); ++e.steps) {
    Sense(plan, x, &map, rng);
    e.last = explorer.Step(x, map, e.steps * kDt);
    if (explorer.turning_at_start()) {  // a turn on the spot at the top rate
      EXPECT_EQ(e.last(0), 0.0);
      EXPECT_EQ(e.last(1), params.control.max_turn_rate_radps);
      ++e.turning_steps;
    }
    e.max_v = std::max(e.max_v, e.last(0));
    e.min_v = std::min(e.min_v, e.last(0));
    e.max_abs_w = std::max(e.max_abs_w, std::abs(e.last(1)));
    x = Drive(x, e.last);
    e.closest_m = std::min(e.closest_m, WallDistance(plan, x.translation()));
  }
  e.done = explorer.done();
  e.targets = explorer.targets_chosen();
  e.coverage =
      Coverage(plan, free_space, map, width_m, height_m, params.frontiers.free_probability);
  return e;
}

void ExpectExploredWithinLimits(const Exploration& e, int min_targets) {
  ASSERT_TRUE(e.done) << "not done after " << e.steps << " steps";
  EXPECT_EQ(e.last(0), 0.0);  // stopped once done
  EXPECT_EQ(e.last(1), 0.0);
  // The start turn is one whole turn: 2π at 1 rad/s in periods of 0.1 s.
  EXPECT_NEAR(e.turning_steps, std::ceil(2.0 * M_PI / kDt), 1.0);
  EXPECT_GE(e.targets, min_targets);
  EXPECT_GE(e.closest_m, GridPathParams{}.robot_radius_m);
  EXPECT_GE(e.min_v, 0.0);
  EXPECT_LE(e.max_v, 0.2 + 1e-12);
  EXPECT_LE(e.max_abs_w, 1.0 + 1e-12);
  EXPECT_GE(e.coverage, 0.9);
}

TEST(GridExplorer, ExploresTwoRoomsRoundAPartitionWithinTheRobotsLimits) {
  // The lower part of the second room is hidden from the first: 90 % needs going in.
  const FreeSpace inside = [](const Eigen::Vector2d&) { return true; };
  ExpectExploredWithinLimits(Explore(TwoRooms(), inside, Pose2(1.2, 1.0, 0.3), 7.0, 3.5, 3000), 2);
}

// Started beside the door in the second room, the robot's first paths round the door's jamb:
// pursuing the full look-ahead past the jamb cut its corner to 0.21 m of the wall (for a 0.3 m
// radius); the point ahead is brought nearer until the line to it keeps the radius.
TEST(GridExplorer, RoundsADoorJambWithoutCuttingItsCorner) {
  const FreeSpace inside = [](const Eigen::Vector2d&) { return true; };
  for (const double heading : {1.6, 3.1}) {
    SCOPED_TRACE(heading);
    ExpectExploredWithinLimits(
        Explore(TwoRooms(), inside, Pose2(4.0, 2.9, heading), 7.0, 3.5, 3000), 2);
  }
}

TEST(GridExplorer, ExploresASmallMazeWithinTheRobotsLimits) {
  // A 10 m square around 2 × 2 blocks of 2 m, corridors of 2 m.
  const FloorPlan maze =
      MakeSquareMaze({.outer_size_m = 10.0, .block_size_m = 2.0, .corridor_width_m = 2.0});
  ASSERT_EQ(maze.walls.size(), 20u);
  const FreeSpace outside_blocks = [](const Eigen::Vector2d& p) {  // blocks span [2, 4], [6, 8]
    const auto in_block = [](double v) { return (v > 2.0 && v < 4.0) || (v > 6.0 && v < 8.0); };
    return !(in_block(p.x()) && in_block(p.y()));
  };
  ExpectExploredWithinLimits(Explore(maze, outside_blocks, Pose2(1.0, 1.0, 0.0), 10.0, 10.0, 8000,
                                     0.1),  // a coarser map: 4 times fewer cells to plan on
                             2);
}

TEST(GridExplorer, SkippingEveryRegionIsDoneAtOnceUntilTheSkipIsLifted) {
  const FloorPlan plan = TwoRooms();
  OccupancyGrid map;
  Rng rng(6);
  const Pose2 x(1.2, 1.0, 0.0);
  Sense(plan, x, &map, rng);  // a half-turn's view: there are frontiers
  ASSERT_FALSE(FindFrontierRegions(map).empty());
  const FrontierSkip skip_all = [](const FrontierRegion&) { return true; };
  const GridExplorerParams params;
  GridExplorer explorer(params);
  for (double t = 0.0; t < params.replan_period_s - 0.5 * kDt; t += kDt) {
    const Control u = explorer.Step(x, map, t, skip_all);
    EXPECT_TRUE(explorer.done());
    EXPECT_EQ(u(0), 0.0);
    EXPECT_EQ(u(1), 0.0);
    EXPECT_FALSE(explorer.target());
    EXPECT_EQ(explorer.targets_chosen(), 0);
  }
  // The same map without the skip has something to explore: the start turn begins.
  GridExplorer fresh(params);
  const Control turn = fresh.Step(x, map, 0.0);
  EXPECT_FALSE(fresh.done());
  EXPECT_TRUE(fresh.target_changed());
  EXPECT_TRUE(fresh.turning_at_start());
  EXPECT_GT(turn(1), 0.0);
  // done() is no latch: the plan is retried replan_period_s after the last one, without the skip.
  const Control u = explorer.Step(x, map, params.replan_period_s, {});
  EXPECT_FALSE(explorer.done());
  EXPECT_TRUE(explorer.target());
  EXPECT_EQ(explorer.targets_chosen(), 1);
  EXPECT_GT(u(1), 0.0);
}

}  // namespace
}  // namespace slamkit::grid_explorer_test
