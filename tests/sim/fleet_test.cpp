#include "slamkit/sim/fleet.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "slamkit/models/extended_observation.hpp"

namespace slamkit {
namespace {

FleetScenarioParams TwoVessels() {
  FleetScenarioParams p;
  p.dt_s = 1.0;
  p.controller.speed_mps = 2.0;
  p.controller.max_turn_rate_radps = 0.2;
  p.sensor.max_range_m = 300.0;
  p.sensor.sigma_range_m = 1.0;
  p.vehicle_sensor = p.sensor;
  const auto square = [](double x0, double y0) {
    RouteParams r;
    r.waypoints_m = {{x0, y0}, {x0 + 100, y0}, {x0 + 100, y0 + 100}, {x0, y0 + 100}};
    r.switch_distance_m = 5.0;
    return r;
  };
  p.vehicles = {{Pose2(0, 0, 0), square(0, 0)}, {Pose2(150, 0, 0), square(150, 0)}};
  return p;
}

LandmarkWorld World() {
  LandmarkWorld w;
  for (int i = 0; i < 6; ++i) w.landmarks.push_back({i, {50.0 * i, 50.0 + 10.0 * (i % 2)}});
  return w;
}

FleetRun SimulateTwo(const FleetScenarioParams& p, std::uint64_t seed) {
  std::vector<Rng> noise;
  for (std::size_t v = 0; v < p.vehicles.size(); ++v) noise.push_back(Rng::ForStream(seed, v));
  return SimulateFleet(p, World(), noise);
}

TEST(Fleet, DrivesEveryRouteAndSensesInTimeOrder) {
  const FleetScenarioParams p = TwoVessels();
  const FleetRun run = SimulateTwo(p, 1);
  ASSERT_EQ(run.landmark_ids.size(), run.log.events.size());
  std::vector<FleetEvent> ordered = run.log.events;
  OrderFleetEvents(ordered);
  for (std::size_t i = 0; i < ordered.size(); ++i) {
    EXPECT_EQ(ordered[i].t_s, run.log.events[i].t_s) << i;
    EXPECT_EQ(ordered[i].kind, run.log.events[i].kind) << i;
    EXPECT_EQ(ordered[i].vehicle, run.log.events[i].vehicle) << i;
  }
  for (const Trajectory& path : run.truth.paths) {
    // Back home after a 400 m loop at 2 m/s.
    EXPECT_GT(path.size(), 150u);
    EXPECT_LT((path.back().pose.translation() - path.front().pose.translation()).norm(), 10.0);
  }
  int vv = 0;
  for (const FleetEvent& e : run.log.events) {
    vv += e.kind == FleetEvent::Kind::kVehicleSighting;
    if (e.kind == FleetEvent::Kind::kLandmarkSighting) {
      EXPECT_EQ(e.landmark, kNoLandmark);
    }
  }
  EXPECT_GT(vv, 100);
}

TEST(Fleet, NoiseFreeSightingsAreTheTrueGeometry) {
  FleetScenarioParams p = TwoVessels();
  p.sensor.sigma_range_m = p.sensor.sigma_bearing_rad = 0.0;
  p.vehicle_sensor = p.sensor;
  const FleetRun run = SimulateTwo(p, 2);
  const auto truth_at = [&](int v, double t) {
    for (const StampedPose& s : run.truth.paths[v]) {
      if (std::abs(s.t_s - t) < 1e-9) return s.pose;
    }
    ADD_FAILURE() << "no truth at " << t;
    return Pose2();
  };
  for (std::size_t i = 0; i < run.log.events.size(); ++i) {
    const FleetEvent& e = run.log.events[i];
    if (e.kind == FleetEvent::Kind::kControl) continue;
    const Pose2 x = truth_at(e.vehicle, e.t_s);
    const RangeBearing z =
        e.kind == FleetEvent::Kind::kVehicleSighting
            ? PredictVehicleSighting(x, truth_at(e.target, e.t_s))
            : PredictRangeBearing(x, World().landmarks[run.landmark_ids[i]].position_m);
    EXPECT_NEAR(e.value.x(), z.range_m, 1e-9);
    EXPECT_NEAR(e.value.y(), z.bearing_rad, 1e-9);
  }
}

// Each vehicle draws from its own stream: vehicle 0 records the same with or without vehicle 1,
// except its sightings of vehicle 1.
TEST(Fleet, AVehiclesRecordDoesNotDependOnTheOthers) {
  FleetScenarioParams two = TwoVessels(), one = two;
  one.vehicles.resize(1);
  const auto own = [](const FleetRun& run) {
    std::vector<FleetEvent> events;
    for (const FleetEvent& e : run.log.events) {
      if (e.vehicle == 0 && e.kind != FleetEvent::Kind::kVehicleSighting) events.push_back(e);
    }
    return events;
  };
  FleetScenarioParams two_blind = two;
  two_blind.vehicle_sensor.max_range_m = 0.0;  // no v-v draws, which come from vehicle 0's stream
  const std::vector<FleetEvent> a = own(SimulateTwo(one, 3)), b = own(SimulateTwo(two_blind, 3));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].value, b[i].value) << i;
  EXPECT_EQ(SimulateTwo(two, 3).log.events.size(), SimulateTwo(two, 3).log.events.size());
  EXPECT_EQ(SimulateTwo(two, 3).log.events.back().value, SimulateTwo(two, 3).log.events.back().value);
}

TEST(Fleet, MessagesAreLostWholeAndCappedToTheNearest) {
  const FleetRun run = SimulateTwo(TwoVessels(), 4);
  Rng rng(1);
  MessageParams lose_all;
  lose_all.loss_probability = 1.0;
  for (const int i : DeliveredEvents(run.log, 0, lose_all, rng)) {
    const FleetEvent& e = run.log.events[i];
    EXPECT_TRUE(e.vehicle == 0 || e.kind == FleetEvent::Kind::kControl);
  }
  MessageParams cap;
  cap.max_sightings = 2;
  const std::vector<int> capped = DeliveredEvents(run.log, 0, cap, rng);
  const std::vector<int> all = DeliveredEvents(run.log, 0, {}, rng);
  EXPECT_EQ(all.size(), run.log.events.size());
  EXPECT_LT(capped.size(), all.size());
  // Per message of vehicle 1 (its sightings at one time, consecutive in the log): at most two
  // kept, and none farther than one left out.
  std::vector<char> in(run.log.events.size(), 0);
  for (const int i : capped) in[i] = 1;
  const auto& events = run.log.events;
  int messages = 0;
  for (std::size_t i = 0; i < events.size();) {
    if (events[i].vehicle != 1 || events[i].kind == FleetEvent::Kind::kControl) {
      ++i;
      continue;
    }
    std::size_t j = i;
    int kept = 0;
    double farthest_kept = 0.0, nearest_dropped = 1e300;
    for (; j < events.size() && events[j].vehicle == 1 && events[j].t_s == events[i].t_s &&
           events[j].kind != FleetEvent::Kind::kControl;
         ++j) {
      kept += in[j];
      if (in[j]) farthest_kept = std::max(farthest_kept, events[j].value.x());
      if (!in[j]) nearest_dropped = std::min(nearest_dropped, events[j].value.x());
    }
    EXPECT_LE(kept, 2);
    EXPECT_LE(farthest_kept, nearest_dropped);
    ++messages;
    i = j;
  }
  EXPECT_GT(messages, 100);
}

}  // namespace
}  // namespace slamkit
