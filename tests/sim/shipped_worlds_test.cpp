// The floor plans shipped in examples/plans/ for issue 10 (SPEC S1): closed worlds whose routes
// keep clear of the walls.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "slamkit/io/floor_plan_reader.hpp"
#include "slamkit/io/waypoints_reader.hpp"
#include "slamkit/sim/floor_plan.hpp"

namespace slamkit {
namespace {

const std::filesystem::path kPlans = std::filesystem::path(SLAMKIT_SOURCE_DIR) / "examples/plans";

double Clearance(const FloorPlan& plan, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const WallSegment& w : plan.walls) {
    const Eigen::Vector2d d = w.second - w.first;
    const double s = std::clamp((p - w.first).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (p - (w.first + s * d)).norm());
  }
  return best;
}

class ShippedWorld : public ::testing::TestWithParam<std::string> {};

// From every point of the route (and half-way between points) every ray meets a wall within
// 60 m: the outline has no gap a ray (or the robot) could leave through. The route keeps 0.5 m
// from the walls.
TEST_P(ShippedWorld, IsClosedAndItsRouteKeepsClear) {
  const FloorPlan plan{ReadFloorPlanFile(kPlans / (GetParam() + ".txt"))};
  const auto route = ReadWaypoints(kPlans / (GetParam() + "_route.txt"));
  ASSERT_GE(route.size(), 2u);
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    for (double s = 0.0; s <= 1.0; s += 0.05) {
      const Eigen::Vector2d p = route[i] + s * (route[i + 1] - route[i]);
      EXPECT_GT(Clearance(plan, p), 0.5) << "leg " << i << " at " << s;
      for (int k = 0; k < 360; ++k) {
        const double a = k * M_PI / 180.0;
        EXPECT_LT(CastRay(plan, p, {std::cos(a), std::sin(a)}, 1e3), 60.0)
            << "a ray leaves the world from (" << p.x() << ", " << p.y() << ") at " << k << "°";
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Plans, ShippedWorld, ::testing::Values("office", "corridor_loop"));

}  // namespace
}  // namespace slamkit
