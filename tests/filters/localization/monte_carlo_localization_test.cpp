#include "slamkit/filters/localization/monte_carlo_localization.hpp"

#include <gtest/gtest.h>

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <memory>

#include "slamkit/core/angle.hpp"
#include "slamkit/filters/localization/map_scan_refiner.hpp"
#include "slamkit/io/grid_writers.hpp"
#include "slamkit/sim/floor_plan_grid.hpp"
#include "slamkit/sim/laser_sim.hpp"

namespace slamkit {
namespace {

// A 20 m × 12 m floor with walls and a box that make every place look different, its map as
// map_server's image, and a 35 m drive through it with drifting odometry.
struct World {
  FloorPlan plan;
  OccupancyImage image;
  GridSimRun run;
};

const World& TheWorld() {
  static const World world = [] {
    World w;
    // Walls through the centres of the map's 5 cm cells: a wall on cell borders marks the cells
    // on both sides, and the map then puts it half a cell from where the scans see it.
    const auto wall = [&](double x0, double y0, double x1, double y1) {
      w.plan.walls.push_back({{x0 + 0.025, y0 + 0.025}, {x1 + 0.025, y1 + 0.025}});
    };
    wall(0, 0, 20, 0), wall(20, 0, 20, 12), wall(20, 12, 0, 12), wall(0, 12, 0, 0);
    wall(6, 0, 6, 7), wall(12, 12, 12, 5), wall(3, 9, 5, 9);
    wall(15, 1.5, 17, 1.5), wall(17, 1.5, 17, 2.5), wall(17, 2.5, 15, 2.5), wall(15, 2.5, 15, 1.5);
    OccupancyGridParams grid;
    grid.resolution_m = 0.05;
    w.image = RenderOccupancyImage(FloorPlanOccupancy(w.plan, grid, {2.0, 2.0}));
    GridSimParams sim;
    sim.sigma_v_mps = 0.05;
    sim.sigma_omega_radps = 0.05;
    sim.route.waypoints_m = {{2, 10}, {9, 10}, {9, 3}, {14, 4}, {18, 8}, {14, 10}};
    sim.route.switch_distance_m = 0.5;
    Rng rng(11);
    w.run = SimulateGridRun(w.plan, sim, Pose2(2, 2, M_PI / 2), rng);
    return w;
  }();
  return world;
}

std::shared_ptr<const LikelihoodField> Field() {
  return std::make_shared<const LikelihoodField>(TheWorld().image);
}

double Error(const Pose2& a, const Pose2& b) { return (a.translation() - b.translation()).norm(); }

// The filter over `scans`, returning the position error at every update.
std::vector<double> UpdateErrors(MonteCarloLocalization& mcl, const std::vector<LaserScan>& scans,
                                 const Trajectory& truth) {
  std::vector<double> errors;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    if (mcl.ProcessScan(scans[i])) errors.push_back(Error(mcl.CurrentPose(), truth[i].pose));
  }
  return errors;
}

TEST(MonteCarloLocalization, TracksFromAKnownStartWhereTheOdometryDrifts) {
  const World& w = TheWorld();
  ASSERT_GT(w.run.scans.size(), 500u);
  const Pose2 odometry_end = w.run.scans.back().odometry;
  ASSERT_GT(Error(odometry_end, w.run.truth.back().pose), 0.5);  // the odometry alone is lost
  MonteCarloLocalization mcl(Field(), MclParams{});
  mcl.InitialiseAt(w.run.truth.front().pose);
  const std::vector<double> errors = UpdateErrors(mcl, w.run.scans, w.run.truth);
  ASSERT_GT(errors.size(), 100u);
  double sum = 0.0;
  for (double e : errors) {
    EXPECT_LT(e, 0.2);
    sum += e;
  }
  EXPECT_LT(sum / double(errors.size()), 0.06);
  EXPECT_TRUE(mcl.Converged());
  EXPECT_LE(mcl.status().particles, MclParams{}.max_particles);
}

TEST(MonteCarloLocalization, GlobalLocalisationConvergesToTheTruePlace) {
  const World& w = TheWorld();
  MonteCarloLocalization mcl(Field(), MclParams{});
  mcl.InitialiseGlobally();
  EXPECT_FALSE(mcl.Converged());
  EXPECT_EQ(mcl.status().particles, MclParams{}.max_particles);
  const std::vector<double> errors = UpdateErrors(mcl, w.run.scans, w.run.truth);
  EXPECT_TRUE(mcl.Converged());
  // KLD-sampling shrinks the set once the particles agree.
  EXPECT_LT(mcl.status().particles, MclParams{}.max_particles / 2);
  for (std::size_t k = errors.size() / 2; k < errors.size(); ++k) EXPECT_LT(errors[k], 0.2) << k;
}

// The robot is carried from where it was at scan 250 to where it is at scan 400 while its
// odometry reports nothing: the scans after the cut come from scan 400 on, their odometry
// continuing from scan 250's.
std::vector<LaserScan> KidnappedScans(Trajectory* truth) {
  const World& w = TheWorld();
  std::vector<LaserScan> scans(w.run.scans.begin(), w.run.scans.begin() + 250);
  *truth = Trajectory(w.run.truth.begin(), w.run.truth.begin() + 250);
  const Pose2 before = w.run.scans[249].odometry;
  for (std::size_t j = 400; j < w.run.scans.size(); ++j) {
    LaserScan s = w.run.scans[j];
    s.odometry = before.Compose(w.run.scans[400].odometry.Between(s.odometry));
    scans.push_back(s);
    truth->push_back(w.run.truth[j]);
  }
  return scans;
}

TEST(MonteCarloLocalization, RandomParticlesRecoverAKidnappedRobot) {
  const World& w = TheWorld();
  Trajectory truth;
  const std::vector<LaserScan> scans = KidnappedScans(&truth);
  ASSERT_GT(Error(w.run.truth[249].pose, w.run.truth[400].pose), 2.0);
  MclParams params;
  params.alpha_slow = 0.001;
  params.alpha_fast = 0.1;
  MonteCarloLocalization mcl(Field(), params);
  mcl.InitialiseAt(truth.front().pose);
  const std::vector<double> errors = UpdateErrors(mcl, scans, truth);
  EXPECT_LT(errors.back(), 0.2);
  // Without them the filter stays where the odometry puts it.
  MclParams off = params;
  off.alpha_slow = off.alpha_fast = 0.0;
  MonteCarloLocalization stays(Field(), off);
  stays.InitialiseAt(truth.front().pose);
  EXPECT_GT(UpdateErrors(stays, scans, truth).back(), 1.0);
}

TEST(MonteCarloLocalization, TheSameSeedGivesTheSameEstimates) {
  const World& w = TheWorld();
  MonteCarloLocalization a(Field(), MclParams{}), b(Field(), MclParams{});
  a.InitialiseGlobally();
  b.InitialiseGlobally();
  for (std::size_t i = 0; i < 200; ++i) {
    a.ProcessScan(w.run.scans[i]);
    b.ProcessScan(w.run.scans[i]);
    ASSERT_EQ(a.CurrentPose().vector(), b.CurrentPose().vector()) << i;
  }
}

// For many bins the bound is the chi-square quantile / 2ε (Fox 2003, Eq. 10); Eq. 11 is the
// Wilson-Hilferty approximation of it.
TEST(MonteCarloLocalization, KldParticleCountIsTheChiSquareBound) {
  for (int bins : {10, 50, 200}) {
    const boost::math::chi_squared chi(bins - 1);
    const double exact = boost::math::quantile(chi, 0.99) / (2.0 * 0.01);
    EXPECT_NEAR(KldParticleCount(bins, 0.01, 2.326), exact, 0.01 * exact) << bins;
  }
  EXPECT_LT(KldParticleCount(10, 0.01, 2.326), KldParticleCount(11, 0.01, 2.326));
  EXPECT_LT(KldParticleCount(10, 0.05, 2.326), KldParticleCount(10, 0.01, 2.326));
}

TEST(MonteCarloLocalization, RejectsParametersOutOfRangeByName) {
  MclParams params;
  params.max_particles = params.min_particles - 1;
  try {
    MonteCarloLocalization mcl(Field(), params);
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_particles"), std::string::npos) << e.what();
  }
}

TEST(MapScanRefiner, MovesAnEstimateOffByCentimetresOntoTheMap) {
  const World& w = TheWorld();
  OccupancyGridParams grid;
  grid.resolution_m = w.image.resolution_m;
  const MapScanRefiner refiner(OccupancyGridFromImage(w.image, {}, grid), DefaultRefinerParams());
  int refined_count = 0, count = 0;
  double sum = 0.0;
  for (std::size_t i = 50; i < w.run.scans.size(); i += 50) {
    const Pose2& truth = w.run.truth[i].pose;
    const Pose2 estimate = truth.Compose(Pose2(0.04, -0.03, 0.02));
    bool refined = false;
    const Pose2 pose = refiner.Refine(w.run.scans[i], estimate, &refined);
    refined_count += refined;
    // The estimate is 5 cm and 20 mrad off; the matcher's finest steps are 5 mm and 2.5 mrad.
    EXPECT_LT(Error(pose, truth), 0.03) << i;
    EXPECT_LT(std::abs(WrapAngle(pose.theta() - truth.theta())), 0.01) << i;
    sum += Error(pose, truth);
    ++count;
  }
  EXPECT_EQ(refined_count, count);
  EXPECT_LT(sum / count, 0.015);
}

}  // namespace
}  // namespace slamkit
