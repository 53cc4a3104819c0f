#include <gtest/gtest.h>

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/rng.hpp"
#include "slamkit/planning/swslam_planner.hpp"

namespace slamkit {
namespace {

// A filter that only has a map: what the planner may read of a filter.
class MapOnlyFilter final : public LandmarkSlamFilter {
 public:
  explicit MapOnlyFilter(LandmarkMap map) : map_(std::move(map)) {}
  void Reset(const Pose2&, const Eigen::Matrix3d&) override {}
  void Predict(const Control&, double, const ControlCovariance*) override {}
  std::vector<AssociationDecision> Update(std::span<const PointObservation>) override { return {}; }
  Pose2 PoseEstimate() const override { return {}; }
  Eigen::Matrix3d PoseCovariance() const override { return Eigen::Matrix3d::Identity(); }
  int NumLandmarks() const override { return static_cast<int>(map_.landmarks.size()); }
  LandmarkMap Map() const override { return map_; }

 private:
  LandmarkMap map_;
};

// Landmarks 0-5 in a tight group at (40, 10), 6-9 spread far apart, 10-39 elsewhere.
LandmarkMap TestMap() {
  LandmarkMap map;
  auto add = [&](double x, double y) {
    MappedLandmark m;
    m.position_m = {x, y};
    map.landmarks.push_back(m);
  };
  for (int i = 0; i < 6; ++i) add(40.0 + 0.2 * i, 10.0 - 0.1 * i);
  add(0.0, 0.0);
  add(0.0, 60.0);
  add(60.0, 60.0);
  add(-30.0, 0.0);
  for (int i = 10; i < 40; ++i) add(100.0 + i, 100.0);
  return map;
}

// A scan's decisions naming landmarks first … first + count − 1 (plus one dropped sighting,
// which must not count).
std::vector<AssociationDecision> Naming(int first, int count) {
  std::vector<AssociationDecision> d;
  for (int i = 0; i < count; ++i) {
    d.push_back({i % 2 ? AssociationDecision::Kind::kNew : AssociationDecision::Kind::kMatched,
                 first + i, 1.0});
  }
  d.push_back({AssociationDecision::Kind::kDropped, -1, 11.0});
  return d;
}

std::vector<bool> Fires(const std::vector<int>& counts, int periods = 3) {
  AreaOfInterestTrigger trigger(periods);
  std::vector<bool> fired;
  for (int n : counts) {
    std::vector<int> landmarks;
    for (int i = 0; i < n; ++i) landmarks.push_back(i);
    fired.push_back(trigger.Add(landmarks));
  }
  return fired;
}

TEST(AreaOfInterestTrigger, FiresOnThreeStrictlyRisingPeriodsOnly) {
  using V = std::vector<bool>;
  EXPECT_EQ(Fires({1, 2, 3}), (V{false, false, true}));
  EXPECT_EQ(Fires({1, 2}), (V{false, false}));                   // a run of 2 is not enough
  EXPECT_EQ(Fires({3, 2, 4}), (V{false, false, false}));         // not monotonic
  EXPECT_EQ(Fires({2, 2, 3}), (V{false, false, false}));         // not strict
  EXPECT_EQ(Fires({1, 2, 2, 3, 4}), (V{false, false, false, false, true}));
  EXPECT_EQ(Fires({5, 1, 2, 3}), (V{false, false, false, true}));
  EXPECT_EQ(Fires({1, 2, 3}, 4), (V{false, false, false}));
  EXPECT_EQ(Fires({1, 2, 3, 4}, 4), (V{false, false, false, true}));
  // Alone it fires on every period of a longer rise: hence the planner's cooldown.
  EXPECT_EQ(Fires({1, 2, 3, 4}), (V{false, false, true, true}));
}

TEST(AreaOfInterestTrigger, CountsDistinctLandmarksAndNotDroppedSightings) {
  EXPECT_EQ(AssociatedLandmarks(Naming(4, 3)), (std::vector<int>{4, 5, 6}));
  std::vector<AssociationDecision> twice = Naming(4, 2);
  twice.push_back(twice.front());
  EXPECT_EQ(AssociatedLandmarks(twice), (std::vector<int>{4, 5}));
  AreaOfInterestTrigger trigger;
  trigger.Add({7});
  trigger.Add({1, 7});
  EXPECT_TRUE(trigger.Add({1, 2, 3}));
  EXPECT_EQ(trigger.AreaLandmarks(), (std::vector<int>{1, 2, 3, 7}));
}

TEST(SwslamPlanner, DetoursToTheLargestClusterThenCoolsDownUntilTheNextRouteWaypoint) {
  const MapOnlyFilter filter(TestMap());
  Rng rng(5);
  SwslamPlanner planner({}, rng);
  RouteProgress at_wp2{2, false};
  // Periods 0-2: 1, 3, 8 landmarks (0-7): the group 0-5 and two far ones, the group the
  // largest of the 3 clusters.
  EXPECT_FALSE(planner.OnPeriod(Naming(0, 1), filter, at_wp2));
  EXPECT_FALSE(planner.OnPeriod(Naming(0, 3), filter, at_wp2));
  const std::optional<Eigen::Vector2d> detour = planner.OnPeriod(Naming(0, 8), filter, at_wp2);
  ASSERT_TRUE(detour);
  EXPECT_LT((*detour - Eigen::Vector2d(40.5, 9.75)).norm(), 1e-9);
  ASSERT_EQ(planner.Sections().size(), 1u);
  EXPECT_EQ(planner.Sections()[0].first_period, 2);
  EXPECT_EQ(planner.Sections()[0].route_waypoint, 2);
  // On the detour, rising counts neither retrigger nor move the target.
  const RouteProgress detouring{2, true};
  for (int n = 11; n < 15; ++n) EXPECT_EQ(planner.OnPeriod(Naming(0, n), filter, detouring), detour);
  // Reached: the route resumes; still rising, but the same section (cooldown).
  for (int n = 15; n < 20; ++n) EXPECT_FALSE(planner.OnPeriod(Naming(0, n), filter, at_wp2));
  ASSERT_EQ(planner.Sections().size(), 1u);
  EXPECT_TRUE(planner.Sections()[0].detour_reached);
  EXPECT_EQ(planner.Sections()[0].end_period, -1);
  // Waypoint 2 reached (period 12): the section ends, and 3 fresh rising periods fire again.
  const RouteProgress at_wp3{3, false};
  EXPECT_FALSE(planner.OnPeriod(Naming(10, 1), filter, at_wp3));
  EXPECT_EQ(planner.Sections()[0].end_period, 12);
  EXPECT_FALSE(planner.OnPeriod(Naming(10, 2), filter, at_wp3));
  EXPECT_TRUE(planner.OnPeriod(Naming(10, 3), filter, at_wp3));
  ASSERT_EQ(planner.Sections().size(), 2u);
  EXPECT_EQ(planner.Sections()[1].first_period, 14);
  EXPECT_EQ(planner.ChosenCentres().size(), 2u);
}

TEST(SwslamPlanner, AbandonsADetourNotReachedInTime) {
  const MapOnlyFilter filter(TestMap());
  Rng rng(5);
  SwslamPlannerParams params;
  params.max_detour_periods = 4;
  SwslamPlanner planner(params, rng);
  planner.OnPeriod(Naming(0, 1), filter, {0, false});
  planner.OnPeriod(Naming(0, 2), filter, {0, false});
  ASSERT_TRUE(planner.OnPeriod(Naming(0, 3), filter, {0, false}));  // period 2
  for (int p = 3; p < 6; ++p) EXPECT_TRUE(planner.OnPeriod(Naming(0, 3), filter, {0, true}));
  EXPECT_FALSE(planner.OnPeriod(Naming(0, 3), filter, {0, true}));  // period 6: 4 periods on
  EXPECT_FALSE(planner.Sections()[0].detour_reached);
  EXPECT_FALSE(planner.OnPeriod(Naming(0, 4), filter, {0, false}));
  EXPECT_EQ(planner.Sections().size(), 1u);
}

// A sparse area (largest cluster under min_cluster_landmarks) opens no section; a dense area is
// taken once, and rising counts around its centre later are not taken again.
TEST(SwslamPlanner, SkipsSparseAreasAndAreasAlreadyVisited) {
  const MapOnlyFilter filter(TestMap());
  Rng rng(5);
  SwslamPlannerParams params;
  params.min_cluster_landmarks = 5;
  params.revisit_radius_m = 10.0;
  SwslamPlanner planner(params, rng);
  // Landmarks 6-9 are far apart: their largest cluster holds 2.
  planner.OnPeriod(Naming(6, 1), filter, {1, false});
  planner.OnPeriod(Naming(6, 2), filter, {1, false});
  EXPECT_FALSE(planner.OnPeriod(Naming(6, 4), filter, {1, false}));
  EXPECT_TRUE(planner.Sections().empty());
  // Landmarks 0-7: the group 0-5 is the largest cluster (6 landmarks): a detour; reached, then
  // waypoint 1 reached.
  planner.OnPeriod(Naming(0, 1), filter, {1, false});
  planner.OnPeriod(Naming(0, 3), filter, {1, false});
  ASSERT_TRUE(planner.OnPeriod(Naming(0, 8), filter, {1, false}));
  planner.OnPeriod(Naming(0, 8), filter, {1, false});
  planner.OnPeriod(Naming(0, 1), filter, {2, false});
  ASSERT_EQ(planner.Sections().size(), 1u);
  EXPECT_NE(planner.Sections()[0].end_period, -1);
  // The same group rising again: within 10 m of the first centre, so no second section.
  planner.OnPeriod(Naming(0, 2), filter, {2, false});
  planner.OnPeriod(Naming(0, 4), filter, {2, false});
  EXPECT_FALSE(planner.OnPeriod(Naming(0, 8), filter, {2, false}));
  EXPECT_EQ(planner.Sections().size(), 1u);
  EXPECT_EQ(planner.ChosenCentres().size(), 1u);
}

TEST(SwslamPlanner, WithoutDetoursOnlyDelimitsTheSections) {
  const MapOnlyFilter filter(TestMap());
  Rng rng(5);
  SwslamPlannerParams params;
  params.detour = false;
  SwslamPlanner planner(params, rng);
  for (int n = 1; n < 8; ++n) EXPECT_FALSE(planner.OnPeriod(Naming(0, n), filter, {1, false}));
  for (int n = 1; n < 4; ++n) EXPECT_FALSE(planner.OnPeriod(Naming(0, n), filter, {2, false}));
  ASSERT_EQ(planner.Sections().size(), 2u);
  EXPECT_EQ(planner.Sections()[0].first_period, 2);
  EXPECT_EQ(planner.Sections()[0].end_period, 7);
  EXPECT_FALSE(planner.Sections()[0].detour_m);
  EXPECT_EQ(planner.Sections()[1].first_period, 9);
  EXPECT_TRUE(planner.ChosenCentres().empty());
}

}  // namespace
}  // namespace slamkit
