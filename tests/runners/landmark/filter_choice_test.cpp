// The filters the command line names (--filter) and the factories behind the names.
#include "slamkit/runners/landmark/filter_choice.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

#include "slamkit/io/error.hpp"
#include "slamkit/runners/landmark/active_monte_carlo.hpp"

namespace slamkit {
namespace {

ScenarioConfig Swslam() {
  return LoadScenario(std::filesystem::path(SLAMKIT_SOURCE_DIR) / "configs" / "swslam.yaml");
}

TEST(FilterChoice, NamesRoundTripAndUnknownNamesAreInputErrors) {
  for (FilterKind kind : {FilterKind::kEkf, FilterKind::kFastSlam1, FilterKind::kFastSlam2}) {
    EXPECT_EQ(ParseFilterKind(FilterName(kind)), kind);
  }
  try {
    ParseFilterKind("ukf");
    FAIL() << "ukf was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ukf"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParsePlannerKind("detour"), InputError);
  EXPECT_EQ(ParsePlannerKind("swslam"), PlannerKind::kSwslam);
  EXPECT_EQ(ParsePlannerKind(PlannerName(PlannerKind::kRoute)), PlannerKind::kRoute);
}

// FastSLAM takes the scenario EKF's association and gates, so that the two are compared on the
// same terms; 1.0 samples from the motion, 2.0 from the observation.
TEST(FilterChoice, FactoriesBuildTheNamedFilterWithTheScenariosSettings) {
  ScenarioConfig c = Swslam();
  c.ekf.association.new_landmark_chi2 = 17.5;
  c.ekf.association_margin_m = 2.5;
  const std::unique_ptr<LandmarkSlamFilter> ekf = FactoryForFilter("ekf", 7, c)();
  ASSERT_NE(dynamic_cast<EkfSlam*>(ekf.get()), nullptr);
  for (const auto& [name, proposal] : {std::pair{"fastslam1", FastSlamProposal::kMotion},
                                       std::pair{"fastslam2", FastSlamProposal::kObservation}}) {
    const std::unique_ptr<LandmarkSlamFilter> filter = FactoryForFilter(name, 7, c)();
    const auto* fastslam = dynamic_cast<FastSlam*>(filter.get());
    ASSERT_NE(fastslam, nullptr) << name;
    EXPECT_EQ(fastslam->params().proposal, proposal) << name;
    EXPECT_EQ(fastslam->params().particles, 7) << name;
    EXPECT_EQ(fastslam->params().new_landmark_chi2, 17.5) << name;
    EXPECT_EQ(fastslam->params().association_margin_m, 2.5) << name;
    EXPECT_EQ(fastslam->params().known_association, c.ekf.known_association()) << name;
  }
  EXPECT_THROW(FactoryForFilter("fastslam2", 0, c), InputError);
  EXPECT_THROW(FactoryForFilter("pf", 10, c), InputError);
}

// The scenario's `fastslam` section reaches FastSLAM, off by default (as FastSlamParams'), and
// delayed sampling stays off with known association, which it cannot take.
TEST(FilterChoice, TheScenariosFastSlamSectionSetsDelayedSampling) {
  ScenarioConfig c = Swslam();
  const auto params = [&c] {
    const std::unique_ptr<LandmarkSlamFilter> filter = FactoryForFilter("fastslam2", 3, c)();
    return dynamic_cast<FastSlam&>(*filter).params();
  };
  EXPECT_FALSE(params().delayed_sampling);
  EXPECT_EQ(params().window_max_landmarks, FastSlamParams{}.window_max_landmarks);
  c.fastslam.delayed_sampling = true;
  c.fastslam.window_max_landmarks = 12;
  EXPECT_TRUE(params().delayed_sampling);
  EXPECT_EQ(params().window_max_landmarks, 12);
  c.ekf.association_method = AssociationMethod::kKnown;
  EXPECT_FALSE(params().delayed_sampling);
}

}  // namespace
}  // namespace slamkit
