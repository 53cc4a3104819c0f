#include "slamkit/runners/cooperative/coop_study.hpp"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "common/temp_dir.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/mrclam_reader.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

const fs::path kMarine = fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "marine_eo.yaml";
const fs::path kMrclamConfig = fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "mrclam.yaml";
const fs::path kDataset6 = fs::path(SLAMKIT_DATASETS_DIR) / "mrclam" / "MRCLAM_Dataset6";

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

// The first two minutes of MRCLAM Dataset 6: every filter beats dead reckoning, and the exact
// mode of each robot is the central filter.
TEST(CoopMrclam, FiltersBeatDeadReckoningOnTheFirstTwoMinutes) {
  if (!fs::exists(kDataset6 / "Barcodes.dat")) GTEST_SKIP() << "no " << kDataset6;
  const CoopConfig config = LoadCoopConfig(kMrclamConfig);
  MrclamSelection window;
  window.duration_s = 120.0;
  const auto [log, truth] = MrclamFleet(ReadMrclam(kDataset6), window);
  const CoopStudyResult r =
      RunCoopLog(log, truth, {}, config.filter,
                 {CoopMode::kDeadReckoning, CoopMode::kMono, CoopMode::kExact, CoopMode::kCentral},
                 config.seed);
  double dead = 0.0, mono = 0.0, exact = 0.0;
  for (std::size_t v = 0; v < 5; ++v) {
    dead += Mode(r, CoopMode::kDeadReckoning).vehicles[v].position_rmse_m / 5.0;
    mono += Mode(r, CoopMode::kMono).vehicles[v].position_rmse_m / 5.0;
    exact += Mode(r, CoopMode::kExact).vehicles[v].position_rmse_m / 5.0;
    EXPECT_NEAR(Mode(r, CoopMode::kExact).vehicles[v].position_rmse_m,
                Mode(r, CoopMode::kCentral).vehicles[v].position_rmse_m, 1e-9);
  }
  EXPECT_LT(mono, dead);
  EXPECT_LT(exact, dead);
}

}  // namespace
}  // namespace slamkit
