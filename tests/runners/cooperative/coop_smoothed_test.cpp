// The "mono-smoothed" mode: the batch estimate of each vehicle's own data.
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "slamkit/runners/cooperative/coop_config.hpp"
#include "slamkit/runners/cooperative/coop_run.hpp"
#include "slamkit/sim/world.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

const fs::path kMarineVessels = fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "marine_eo.yaml";

CoopConfig ShortNoisyMarine() {
  CoopConfig c = LoadCoopConfig(kMarineVessels);
  c.scenario.max_steps = 600;
  return c;
}

// The marine vessels with neither control nor sensor noise in the simulation (the filters keep
// the config's): the sightings and controls agree exactly with the true paths.
FleetRun NoiseFreeRun(const CoopConfig& config) {
  FleetScenarioParams scenario = config.scenario;
  scenario.motion = {0.0, 0.0};
  scenario.sensor.sigma_range_m = 0.0;
  scenario.sensor.sigma_bearing_rad = 0.0;
  scenario.vehicle_sensor.sigma_range_m = 0.0;
  scenario.vehicle_sensor.sigma_bearing_rad = 0.0;
  std::vector<Rng> noise = {Rng::ForStream(config.seed, 0), Rng::ForStream(config.seed, 1)};
  return SimulateFleet(scenario, MakeWorld(scenario.world), noise);
}

// Noise-free data has a zero-residual solution, the truth: the smoother must reach it from the
// Mono filter's path (which is not exact: its prediction noise keeps it off the truth), with
// every node's motion composed from the held controls as the simulation drove.
TEST(CoopSmoothed, RecoversANoiseFreeFleetExactly) {
  const CoopConfig c = ShortNoisyMarine();
  const FleetRun run = NoiseFreeRun(c);
  const CoopModeResult smoothed =
      RunCoopMode(run.log, run.truth, run.landmark_ids, CoopMode::kMonoSmoothed, c.filter, c.seed);
  ASSERT_EQ(smoothed.vehicles.size(), 2u);
  for (const CoopVehicleTrace& v : smoothed.vehicles) {
    ASSERT_GT(v.estimate.size(), 100u);
    EXPECT_LT(v.position_rmse_m, 1e-4);
    EXPECT_LT(v.position_aligned_rmse_m, 1e-4);
    EXPECT_LT(v.heading_rmse_rad, 1e-6);
    EXPECT_LT(v.map_rmse_m, 1e-4);
    EXPECT_EQ(v.counts.landmark_dropped, 0);
  }
}

// A sighting far beyond the gate is dropped, and the rest are again solved exactly; without
// the gate the same sighting pulls the solution off the truth.
TEST(CoopSmoothed, DropsASightingBeyondTheGate) {
  CoopConfig c = ShortNoisyMarine();
  FleetRun run = NoiseFreeRun(c);
  for (FleetEvent& e : run.log.events) {
    if (e.kind == FleetEvent::Kind::kLandmarkSighting && e.vehicle == 0 && e.t_s > 200.0) {
      e.value.x() += 500.0;  // 50 σ of the radar's range
      break;
    }
  }
  c.filter.known_gate_chi2 = 13.8;
  const CoopModeResult gated =
      RunCoopMode(run.log, run.truth, run.landmark_ids, CoopMode::kMonoSmoothed, c.filter, c.seed);
  EXPECT_EQ(gated.vehicles[0].counts.landmark_dropped, 1);
  EXPECT_LT(gated.vehicles[0].position_rmse_m, 1e-4);
  c.filter.known_gate_chi2 = std::numeric_limits<double>::infinity();
  const CoopModeResult ungated =
      RunCoopMode(run.log, run.truth, run.landmark_ids, CoopMode::kMonoSmoothed, c.filter, c.seed);
  EXPECT_EQ(ungated.vehicles[0].counts.landmark_dropped, 0);
  EXPECT_GT(ungated.vehicles[0].position_rmse_m, 1e-2);
}

// Dead reckoning of noise-free controls from a wrong start pose is the true path moved by one
// rigid transform: its error is all frame, and the aligned error must remove it.
TEST(CoopScoring, TheAlignedErrorRemovesAWrongFrame) {
  const CoopConfig c = ShortNoisyMarine();
  FleetRun run = NoiseFreeRun(c);
  const Pose2 truth_start = run.log.start_poses[0];
  run.log.start_poses[0] =
      Pose2(truth_start.x() + 30.0, truth_start.y() - 20.0, truth_start.theta() + 0.05);
  const CoopModeResult dr =
      RunCoopMode(run.log, run.truth, run.landmark_ids, CoopMode::kDeadReckoning, c.filter, c.seed);
  EXPECT_GT(dr.vehicles[0].position_rmse_m, 10.0);
  EXPECT_LT(dr.vehicles[0].position_aligned_rmse_m, 1e-6);
  EXPECT_LT(dr.vehicles[1].position_rmse_m, 1e-6);  // its start was left as it was
}

}  // namespace
}  // namespace slamkit
