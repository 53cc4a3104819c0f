#include "slamkit/runners/cooperative/coop_study.hpp"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "common/temp_dir.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/sim/world.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

const fs::path kMarine = fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "marine_eo.yaml";
const fs::path kMrclamConfig = fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "mrclam.yaml";

// The marine scenario cut to its first 600 s.
CoopConfig ShortMarine(int runs) {
  CoopConfig c = LoadCoopConfig(kMarine);
  c.scenario.max_steps = 600;
  c.runs = runs;
  return c;
}

const CoopModeSummary& Mode(const CoopStudyResult& r, CoopMode mode) {
  for (const CoopModeSummary& m : r.modes) {
    if (m.mode == mode) return m;
  }
  throw std::logic_error("mode did not run");
}

TEST(CoopStudy, ExactModeIsTheCentralFilterAndSharingBeatsMono) {
  const CoopStudyResult r = RunCoopStudy(
      ShortMarine(3), {CoopMode::kMono, CoopMode::kExtended, CoopMode::kExact, CoopMode::kCentral});
  ASSERT_EQ(r.modes.size(), 4u);
  const CoopModeSummary& mono = Mode(r, CoopMode::kMono);
  const CoopModeSummary& eo = Mode(r, CoopMode::kExtended);
  const CoopModeSummary& exact = Mode(r, CoopMode::kExact);
  const CoopModeSummary& central = Mode(r, CoopMode::kCentral);
  for (std::size_t v = 0; v < 2; ++v) {
    // Every message delivered: each vehicle's exact filter is the centralised one.
    EXPECT_NEAR(exact.vehicles[v].position_rmse_m, central.vehicles[v].position_rmse_m, 1e-9);
    EXPECT_NEAR(exact.vehicles[v].anees, central.vehicles[v].anees, 1e-9);
    // Sharing shrinks the position covariance: SPEC S3's improvement ratio is positive.
    EXPECT_GT(eo.vehicles[v].improvement_ratio_mean_pct, 0.0) << v;
    EXPECT_GT(exact.vehicles[v].improvement_ratio_mean_pct, 0.0) << v;
    EXPECT_LT(exact.vehicles[v].position_cov_norm.back(), mono.vehicles[v].position_cov_norm.back());
    EXPECT_FALSE(exact.vehicles[v].t_s.empty());
  }
  EXPECT_GT(eo.counts.extended, 0);
  EXPECT_GT(exact.counts.vehicle_updates, 0);
}

// The runs go in parallel batches and are summed in run order: one thread and two give the same
// figures, to the bit.
TEST(CoopStudy, FiguresDoNotDependOnTheThreadCount) {
  CoopConfig c = ShortMarine(5);
  c.filter.messages.loss_probability = 0.3;  // message draws per run, too
  const std::vector<CoopMode> modes = {CoopMode::kMono, CoopMode::kExtended, CoopMode::kExact};
  const CoopStudyResult one = RunCoopStudy(c, modes, {}, 1);
  const CoopStudyResult two = RunCoopStudy(c, modes, {}, 2);
  for (std::size_t m = 0; m < modes.size(); ++m) {
    for (std::size_t v = 0; v < 2; ++v) {
      const CoopVehicleSummary& a = one.modes[m].vehicles[v];
      const CoopVehicleSummary& b = two.modes[m].vehicles[v];
      EXPECT_EQ(a.position_rmse_m, b.position_rmse_m);
      EXPECT_EQ(a.anees, b.anees);
      EXPECT_EQ(a.position_cov_norm, b.position_cov_norm);
      EXPECT_EQ(a.improvement_ratio_pct, b.improvement_ratio_pct);
    }
    EXPECT_EQ(one.modes[m].first_run.vehicles[0].estimate.size(),
              two.modes[m].first_run.vehicles[0].estimate.size());
  }
}

TEST(CoopStudy, LostMessagesLeaveTheExactFilterBetweenMonoAndCentral) {
  CoopConfig c = ShortMarine(1);
  c.filter.messages.loss_probability = 0.5;
  const CoopStudyResult r =
      RunCoopStudy(c, {CoopMode::kMono, CoopMode::kExact, CoopMode::kCentral});
  for (std::size_t v = 0; v < 2; ++v) {
    const double mono = Mode(r, CoopMode::kMono).vehicles[v].position_cov_norm.back();
    const double exact = Mode(r, CoopMode::kExact).vehicles[v].position_cov_norm.back();
    const double central = Mode(r, CoopMode::kCentral).vehicles[v].position_cov_norm.back();
    EXPECT_LT(exact, mono) << v;
    EXPECT_GT(exact, central) << v;
  }
}

// The association agreement reads the true ids: with known association it is 1, with nearest
// neighbour on the marine scenario's well-separated features it is high, and against ids
// drawn at random for each sighting (the same filter run) it collapses.
TEST(CoopRun, AssociationAgreementScoresTheFilterAgainstTheTrueIds) {
  CoopConfig c = ShortMarine(1);
  const LandmarkWorld world = MakeWorld(c.scenario.world);
  std::vector<Rng> noise = {Rng::ForStream(c.seed, 0), Rng::ForStream(c.seed, 1)};
  const FleetRun run = SimulateFleet(c.scenario, world, noise);
  const CoopModeResult known =
      RunCoopMode(run.log, run.truth, run.landmark_ids, CoopMode::kMono, c.filter, c.seed);
  c.filter.known_association = false;
  c.filter.filter.ekf.association_method = AssociationMethod::kNearestNeighbour;
  const CoopModeResult nn =
      RunCoopMode(run.log, run.truth, run.landmark_ids, CoopMode::kMono, c.filter, c.seed);
  std::vector<LandmarkId> random_ids = run.landmark_ids;
  Rng rng(5);
  for (LandmarkId& id : random_ids) {
    if (id != kNoLandmark) id = world.landmarks[rng.NextU64() % world.landmarks.size()].id;
  }
  const CoopModeResult scrambled =
      RunCoopMode(run.log, run.truth, random_ids, CoopMode::kMono, c.filter, c.seed);
  for (std::size_t v = 0; v < 2; ++v) {
    EXPECT_DOUBLE_EQ(known.vehicles[v].association_agreement, 1.0) << v;
    EXPECT_GT(nn.vehicles[v].association_agreement, 0.8) << v;
    EXPECT_LT(scrambled.vehicles[v].association_agreement, 0.5) << v;
    // The same filter run: only the scoring differs.
    EXPECT_EQ(scrambled.vehicles[v].position_rmse_m, nn.vehicles[v].position_rmse_m) << v;
  }
}

// The marine simulation lists vehicle 0's scan of each time before vehicle 1's; each filter
// still extends the other's shared scans through its own v-v sighting of the same time.
TEST(CoopRun, EveryVehicleOfASynchronousFleetMakesExtendedObservations) {
  const CoopConfig c = ShortMarine(1);
  const LandmarkWorld world = MakeWorld(c.scenario.world);
  std::vector<Rng> noise = {Rng::ForStream(c.seed, 0), Rng::ForStream(c.seed, 1)};
  const FleetRun run = SimulateFleet(c.scenario, world, noise);
  const CoopModeResult eo =
      RunCoopMode(run.log, run.truth, run.landmark_ids, CoopMode::kExtended, c.filter, c.seed);
  const long a = eo.vehicles[0].counts.extended, b = eo.vehicles[1].counts.extended;
  EXPECT_GT(a, 0);
  EXPECT_GT(b, a / 2);  // the same routes and sensors: about as many
  EXPECT_EQ(a + b, eo.counts.extended);
}

// With messages up to D late, a vehicle's estimate at real time T may use the others' messages
// of times up to T − D only: cutting the other vessel's events after T* must leave every
// estimate up to T* + D as it was, bit for bit. Without the lag the cut changes estimates
// before T* + D (the test can tell). The lag costs accuracy: the covariance grows with D.
TEST(CoopRun, DelayedMessagesAreUsedOnlyOnceTheyHaveArrived) {
  CoopConfig c = ShortMarine(1);
  const LandmarkWorld world = MakeWorld(c.scenario.world);
  std::vector<Rng> noise = {Rng::ForStream(c.seed, 0), Rng::ForStream(c.seed, 1)};
  const FleetRun run = SimulateFleet(c.scenario, world, noise);
  constexpr double kCut_s = 300.0, kDelay_s = 20.0;
  FleetLog cut = run.log;
  std::erase_if(cut.events, [&](const FleetEvent& e) {
    return e.vehicle == 1 && e.t_s > run.log.events.front().t_s + kCut_s;
  });
  const double cut_time = run.log.events.front().t_s + kCut_s;
  const auto estimates_until = [](const CoopModeResult& r, double t) {
    std::vector<Eigen::Vector3d> out;
    for (const StampedPose& p : r.vehicles[0].estimate) {
      if (p.t_s <= t) out.push_back(p.pose.vector());
    }
    return out;
  };
  for (const CoopMode mode : {CoopMode::kExact, CoopMode::kExtended}) {
    for (const double delay : {0.0, kDelay_s}) {
      c.filter.messages.delay_s = delay;
      const CoopModeResult whole =
          RunCoopMode(run.log, run.truth, run.landmark_ids, mode, c.filter, c.seed);
      const CoopModeResult part =
          RunCoopMode(cut, run.truth, run.landmark_ids, mode, c.filter, c.seed);
      const auto a = estimates_until(whole, cut_time + kDelay_s);
      const auto b = estimates_until(part, cut_time + kDelay_s);
      ASSERT_EQ(a.size(), b.size());
      ASSERT_GT(a.size(), 250u);
      if (delay > 0.0) {
        EXPECT_EQ(a, b) << CoopModeName(mode);
        EXPECT_NEAR(whole.vehicles[0].estimate.front().t_s, run.log.events.front().t_s + delay,
                    1.5);
      } else {
        EXPECT_NE(a, b) << CoopModeName(mode);
      }
    }
  }
  // The exact mode's mean covariance norm grows with the lag, and its estimates are still
  // consistent with their covariance (the pose moved on by the controls carries their noise).
  double previous = 0.0;
  for (const double delay : {0.0, 10.0, 40.0}) {
    c.filter.messages.delay_s = delay;
    const CoopModeResult r =
        RunCoopMode(run.log, run.truth, run.landmark_ids, CoopMode::kExact, c.filter, c.seed);
    double norm = 0.0;
    for (double n : r.vehicles[0].position_cov_norm) norm += n;
    norm /= static_cast<double>(r.vehicles[0].position_cov_norm.size());
    EXPECT_GT(norm, previous) << delay;
    EXPECT_LT(r.vehicles[0].mean_nees, 9.0) << delay;
    previous = norm;
  }
}

// A filter behind real time records later times than Mono: IR pairs each record with Mono's at
// the same time or the latest before it, and leaves out records before Mono's first.
TEST(CoopRun, ImprovementRatioPairsRecordsByTime) {
  const std::vector<double> mono_t = {10, 11, 12, 13}, mono_norm = {1, 2, 4, 8};
  const std::vector<double> ir = ImprovementRatio(mono_t, mono_norm, {9, 12, 13, 14.5}, {1, 2, 6, 2});
  ASSERT_EQ(ir.size(), 3u);
  EXPECT_DOUBLE_EQ(ir[0], 50.0);   // 12 against 12
  EXPECT_DOUBLE_EQ(ir[1], 25.0);   // 13 against 13
  EXPECT_DOUBLE_EQ(ir[2], 75.0);   // 14.5 against 13, the latest before
}

class CoopConfigFile : public testing::TempDirTest {};

TEST_F(CoopConfigFile, MistakesNameTheFileTheLineAndTheKey) {
  const struct {
    const char* text;
    const char* expected;
  } cases[] = {
      {"runs: 0\n", "runs"},
      {"filter:\n  sigma_v_mps: -1\n", "filter.sigma_v_mps"},
      {"vehicles:\n  - start: [0, 0]\n    waypoints_m: [[1, 1], [2, 2]]\n", "start"},
      {"vehicles:\n  - start: [0, 0, 0]\n    waypoints_m: [[1, 1]]\n", "waypoints_m"},
      {"messages: {loss_probability: nan}\n", "loss_probability"},
      {"filter:\n  control_noise_density: [1]\n", "control_noise_density"},
      {"sensr: {}\n", "sensr"},
      {"ekf: {association: known}\nfilter:\n  known_association: false\n", "known_association"},
  };
  for (const auto& c : cases) {
    const fs::path path = WriteFile("coop.yaml", c.text);
    try {
      LoadCoopConfig(path);
      ADD_FAILURE() << "no error for " << c.text;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("coop.yaml"), std::string::npos) << what;
      EXPECT_NE(what.find(c.expected), std::string::npos) << what;
    }
  }
}

TEST(CoopConfig, TheShippedFilesLoadAndTheirParamsRoundTrip) {
  const CoopConfig marine = LoadCoopConfig(kMarine);
  EXPECT_EQ(marine.scenario.vehicles.size(), 2u);
  EXPECT_EQ(marine.scenario.world.uniform.count, 10);
  const CoopConfig mrclam = LoadCoopConfig(kMrclamConfig);
  ASSERT_TRUE(mrclam.filter.control_noise_density.has_value());
  const nlohmann::json j = CoopConfigJson(mrclam);
  EXPECT_NEAR(j["filter"]["control_noise_density"][1].get<double>(), 8.0, 1e-9);
}

}  // namespace
}  // namespace slamkit
