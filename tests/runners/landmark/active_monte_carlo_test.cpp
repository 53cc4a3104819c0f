// The closed-loop Monte Carlo of SPEC S2 (RunActiveMonteCarlo) and the sections it measures.
#include "slamkit/runners/landmark/active_monte_carlo.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <vector>

#include "runners/landmark/short_swslam.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

ScenarioConfig Load(const char* name) {
  return LoadScenario(fs::path(SLAMKIT_SOURCE_DIR) / "configs" / name);
}

ActiveMonteCarloParams Params(int runs, std::uint64_t seed, int threads) {
  ActiveMonteCarloParams p;
  p.mc.runs = runs;
  p.mc.seed = seed;
  p.mc.threads = threads;
  return p;
}

// Issue 11: on the route the closed loop is the open-loop Monte Carlo, figure for figure (same
// streams per run, same aggregation), with nearest-neighbour association so that the planner's
// trigger sees real decisions.
TEST(ActiveMonteCarlo, RoutePlannerGivesTheOpenLoopFigures) {
  ScenarioConfig c = Load("short.yaml");
  c.ekf.association_method = AssociationMethod::kNearestNeighbour;
  const ActiveMonteCarloParams params = Params(4, 11, 2);
  const MonteCarloResult open = RunMonteCarlo(c, params.mc);
  const ActiveMonteCarloResult closed =
      RunActiveMonteCarlo(c, EkfSlamFactory(c), PlannerKind::kRoute, params);
  EXPECT_EQ(closed.planner, PlannerKind::kRoute);
  EXPECT_EQ(closed.mc.t_s, open.t_s);
  EXPECT_EQ(closed.mc.anees, open.anees);
  EXPECT_EQ(closed.mc.position_rmse_m, open.position_rmse_m);
  EXPECT_EQ(closed.mc.heading_rmse_rad, open.heading_rmse_rad);
  EXPECT_EQ(closed.mc.anees_mean, open.anees_mean);
  EXPECT_EQ(closed.mc.anees_fraction_in_band, open.anees_fraction_in_band);
  EXPECT_EQ(closed.mc.rmse.position_m, open.rmse.position_m);
  EXPECT_EQ(closed.mc.rmse.heading_rad, open.rmse.heading_rad);
  EXPECT_EQ(closed.mc.map_rmse_mean_m, open.map_rmse_mean_m);
  EXPECT_EQ(closed.mc.association.correct, open.association.correct);
  EXPECT_EQ(closed.mc.runs_at_step, std::vector<int>(open.t_s.size(), 4));
  for (const ActiveRunTrace& trace : closed.traces) EXPECT_TRUE(trace.centres_m.empty());
}

TEST(ActiveMonteCarlo, SameSeedSameResultWhateverTheThreadCount) {
  constexpr int kRuns = 2;
  const ScenarioConfig c = ShortSwslam();
  const ActiveMonteCarloResult one =
      RunActiveMonteCarlo(c, EkfSlamFactory(c), PlannerKind::kSwslam, Params(kRuns, 3, 1));
  const ActiveMonteCarloResult two =
      RunActiveMonteCarlo(c, EkfSlamFactory(c), PlannerKind::kSwslam, Params(kRuns, 3, 2));
  EXPECT_EQ(one.mc.anees, two.mc.anees);
  EXPECT_EQ(one.mc.position_rmse_m, two.mc.position_rmse_m);
  EXPECT_EQ(one.mc.runs_at_step, two.mc.runs_at_step);
  ASSERT_EQ(one.traces.size(), std::size_t{kRuns});
  ASSERT_EQ(two.traces.size(), std::size_t{kRuns});
  int detours = 0;
  for (std::size_t k = 0; k < kRuns; ++k) {
    EXPECT_EQ(one.traces[k].centres_m, two.traces[k].centres_m) << k;
    EXPECT_EQ(one.traces[k].steps, two.traces[k].steps) << k;
    ASSERT_EQ(one.traces[k].sections.size(), two.traces[k].sections.size()) << k;
    for (std::size_t i = 0; i < one.traces[k].sections.size(); ++i) {
      EXPECT_EQ(one.traces[k].sections[i].observations, two.traces[k].sections[i].observations);
    }
    detours += static_cast<int>(one.traces[k].centres_m.size());
  }
  EXPECT_GT(detours, 0) << "the test needs SWSLAM to leave the route";
  ASSERT_EQ(one.sections.size(), two.sections.size());
  for (std::size_t i = 0; i < one.sections.size(); ++i) {
    EXPECT_EQ(one.sections[i].observations_per_landmark, two.sections[i].observations_per_landmark);
  }
}

// With detours the runs differ in length: each step's figures are over the runs that reached it.
TEST(ActiveMonteCarlo, StepSeriesAverageTheRunsStillRunning) {
  constexpr int kRuns = 3;
  const ScenarioConfig c = ShortSwslam();
  const ActiveMonteCarloResult r =
      RunActiveMonteCarlo(c, EkfSlamFactory(c), PlannerKind::kSwslam, Params(kRuns, 8, 2));
  ASSERT_EQ(r.mc.runs.size(), std::size_t{kRuns});
  std::set<std::size_t> lengths;
  std::size_t longest = 0;
  for (const RunResult& run : r.mc.runs) {
    lengths.insert(run.nees.size());
    longest = std::max(longest, run.nees.size());
  }
  ASSERT_GT(lengths.size(), 1u) << "the test needs runs of different lengths";
  ASSERT_EQ(r.mc.anees.size(), longest);
  ASSERT_EQ(r.mc.t_s.size(), longest);
  for (std::size_t k = 0; k < longest; ++k) {
    double sum = 0.0, sq = 0.0;
    int n = 0;
    for (const RunResult& run : r.mc.runs) {
      if (k >= run.nees.size()) continue;
      sum += run.nees[k];
      sq += run.errors[k].head<2>().squaredNorm();
      ++n;
    }
    ASSERT_EQ(r.mc.runs_at_step[k], n) << k;
    EXPECT_DOUBLE_EQ(r.mc.anees[k], sum / n) << k;
    EXPECT_DOUBLE_EQ(r.mc.position_rmse_m[k], std::sqrt(sq / n)) << k;
  }
  EXPECT_EQ(r.mc.runs_at_step.front(), kRuns);
  EXPECT_LT(r.mc.runs_at_step.back(), kRuns);
  EXPECT_TRUE(std::is_sorted(r.mc.runs_at_step.rbegin(), r.mc.runs_at_step.rend()));
}

TEST(ActiveMonteCarlo, SectionMeansAreOverTheRunsThatHaveTheSection) {
  SectionStats a, b, c;
  a.observations = 10;
  a.observations_per_landmark = 2.0;
  b.observations = 30;
  b.observations_per_landmark = 4.0;
  c.observations = 7;
  c.observations_per_landmark = 7.0;
  const std::vector<SectionMean> means = MeanSections({{a, c}, {b}});
  ASSERT_EQ(means.size(), 2u);
  EXPECT_EQ(means[0].runs, 2);
  EXPECT_DOUBLE_EQ(means[0].observations, 20.0);
  EXPECT_DOUBLE_EQ(means[0].observations_per_landmark, 3.0);
  EXPECT_EQ(means[1].index, 1);
  EXPECT_EQ(means[1].runs, 1);
  EXPECT_DOUBLE_EQ(means[1].observations, 7.0);
}

std::vector<PeriodState> Periods(const std::vector<std::pair<double, int>>& x_and_leg) {
  std::vector<PeriodState> out;
  for (const auto& [x, leg] : x_and_leg) out.push_back({Eigen::Vector2d(x, 0.0), leg});
  return out;
}

// A section starts, on the other run, at the period of the same leg nearest to where it was
// detected, and ends where that run leaves the leg.
TEST(CarrySections, StartNearestOnTheSameLegAndEndWithIt) {
  const std::vector<PeriodState> source = Periods({{0, 0}, {5, 0}, {10, 1}, {12, 1}, {30, 2}});
  const std::vector<PeriodState> target =
      Periods({{0, 0}, {4, 0}, {8, 1}, {11, 1}, {12.4, 1}, {16, 1}, {20, 2}, {25, 2}});
  RouteSection s;
  s.first_period = 3;  // x = 12 on leg 1
  s.end_period = 4;
  s.route_waypoint = 2;
  s.detour_m = Eigen::Vector2d(40, 40);
  RouteSection last;
  last.first_period = 4;  // leg 2, which the target never leaves
  const std::vector<RouteSection> carried = CarrySections({s, last}, source, target);
  ASSERT_EQ(carried.size(), 2u);
  EXPECT_EQ(carried[0].first_period, 4);  // x = 12.4, nearer than 11 and 16
  EXPECT_EQ(carried[0].end_period, 6);    // the first period of leg 2
  EXPECT_EQ(carried[0].route_waypoint, 2);
  EXPECT_FALSE(carried[0].detour_m.has_value());
  EXPECT_EQ(carried[1].first_period, 7);  // x = 25 nearest to 30 on leg 2
  EXPECT_EQ(carried[1].end_period, -1);
  // A leg the target never drove: an empty section.
  const std::vector<PeriodState> short_target = Periods({{0, 0}, {4, 0}});
  const std::vector<RouteSection> empty = CarrySections({s}, source, short_target);
  ASSERT_EQ(empty.size(), 1u);
  EXPECT_EQ(empty[0].first_period, empty[0].end_period);
  EXPECT_THROW(CarrySections({RouteSection{9, -1, 0, {}, false}}, source, target),
               std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
