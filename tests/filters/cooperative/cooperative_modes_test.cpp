// The exact cooperative mode against the centralised filter and a dense EKF, and the seed's
// formulation's over-confidence where one vehicle sighting extends many landmark sightings.
#include "slamkit/filters/cooperative/cooperative_ekf_slam.hpp"

#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "filters/dense_reference.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/eval/consistency.hpp"
#include "slamkit/models/extended_observation.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/unicycle.hpp"
#include "fleet.hpp"

namespace slamkit {
namespace {

using coop_test::Fleet;
using coop_test::kMotion;
using coop_test::kR;
using coop_test::MakeFilter;
using coop_test::PositionTrace;
using coop_test::WideSensor;

TEST(CooperativeEkfSlam, ExactModeIsTheCentralisedFilterAndTheDenseEkf) {
  Fleet fleet;
  fleet.truth = {Pose2(0, 0, 0.2), Pose2(6, -3, 1.4)};
  fleet.landmarks = {{4, 4}, {9, 1}, {2, -5}};
  const Eigen::Matrix3d start_cov = Eigen::Vector3d(0.04, 0.04, 0.001).asDiagonal();
  CooperativeEkfSlam vehicle0 = MakeFilter(CooperativeMode::kExact, 2, 0);
  CooperativeEkfSlam central = MakeFilter(CooperativeMode::kExact, 2, -1);
  vehicle0.Reset(fleet.truth, start_cov);
  central.Reset(fleet.truth, start_cov);
  testing::DenseEkf dense;
  dense.x.resize(6);
  dense.x << fleet.truth[0].vector(), fleet.truth[1].vector();
  dense.P = Eigen::MatrixXd::Zero(6, 6);
  dense.P.topLeftCorner(3, 3) = start_cov;
  dense.P.bottomRightCorner(3, 3) = start_cov;
  dense.angles = {2, 5};
  const UnicycleModel motion(kMotion);
  std::vector<int> landmark_offset(3, -1);
  const std::vector<FleetScan> scans = {fleet.Scan(0, {0, 1}, {}), fleet.Scan(1, {1, 2}, {0}),
                                        fleet.Scan(0, {2}, {1}), fleet.Scan(1, {0}, {})};
  for (const FleetScan& scan : scans) {
    Control u(2);
    u << 0.8, 0.1;
    for (int v = 0; v < 2; ++v) {
      vehicle0.Predict(v, u, 0.5);
      central.Predict(v, u, 0.5);
      Eigen::Matrix3d F;
      ControlJacobian G;
      const Pose2 moved = motion.Move(Pose2(Eigen::Vector3d(dense.x.segment<3>(3 * v))), u, 0.5,
                                      &F, &G);
      Eigen::MatrixXd Fd = Eigen::MatrixXd::Identity(dense.x.size(), dense.x.size());
      Fd.block<3, 3>(3 * v, 3 * v) = F;
      Eigen::MatrixXd Gd = dense.Spread(G.transpose(), 3 * v).transpose();
      dense.P = Fd * dense.P * Fd.transpose() + Gd * motion.Noise(u, 0.5) * Gd.transpose();
      dense.x.segment<3>(3 * v) = moved.vector();
    }
    vehicle0.Update(scan);
    central.Update(scan);
    const int v = scan.vehicle;
    const auto pose = [&](int w) { return Pose2(Eigen::Vector3d(dense.x.segment<3>(3 * w))); };
    for (const VehicleObservation& vv : scan.vehicles) {
      Eigen::Matrix<double, 2, 3> J_a, J_b;
      const RangeBearing z = PredictVehicleSighting(pose(v), pose(vv.target), &J_a, &J_b);
      const Eigen::MatrixXd H = dense.Spread(J_a, 3 * v) + dense.Spread(J_b, 3 * vv.target);
      dense.Update(Eigen::Vector2d(vv.z.x() - z.range_m, WrapAngle(vv.z.y() - z.bearing_rad)),
                   H, vv.R);
    }
    for (const PointObservation& obs : scan.landmarks) {
      const int l = static_cast<int>(obs.id);
      if (landmark_offset[l] < 0) {
        Eigen::Matrix<double, 2, 3> J_x;
        Eigen::Matrix2d J_z;
        const Eigen::Vector2d m = InvertRangeBearing(pose(v), {obs.z.x(), obs.z.y()}, &J_x, &J_z);
        landmark_offset[l] = static_cast<int>(dense.x.size());
        dense.Augment(m, dense.Spread(J_x, 3 * v), J_z, obs.R);
        continue;
      }
      Eigen::Matrix<double, 2, 3> J_x;
      Eigen::Matrix2d J_l;
      const RangeBearing z = PredictRangeBearing(
          pose(v), dense.x.segment<2>(landmark_offset[l]), &J_x, &J_l);
      dense.Update(Eigen::Vector2d(obs.z.x() - z.range_m, WrapAngle(obs.z.y() - z.bearing_rad)),
                   dense.Spread(J_x, 3 * v) + dense.Spread(J_l, landmark_offset[l]), obs.R);
    }
  }
  ASSERT_EQ(central.StateSize(), dense.x.size());
  EXPECT_LT(testing::MaxAbsDiff(vehicle0.ekf().State(), central.ekf().State()), 1e-9);
  EXPECT_LT(testing::MaxAbsDiff(vehicle0.ekf().Covariance(), central.ekf().Covariance()), 1e-9);
  // Landmarks were created in the same order (0, 1, 2), so the layouts agree.
  EXPECT_LT(testing::MaxAbsDiff(central.ekf().State(), dense.x), 1e-9);
  EXPECT_LT(testing::MaxAbsDiff(central.ekf().Covariance(), dense.P), 1e-9);
}

// One coarse v-v sighting extends b's sightings of eight landmarks new to a; a then drives on
// with poor odometry and sights them itself. The seed's formulation places the eight as
// independent of each other, though they share the v-v sighting's error, and a's new pose then
// trusts their average as if that error had averaged out. The exact mode places them from b's
// pose block, correlated through the v-v update. Over many trials the seed's pose NEES of a
// lies far above the 95 % band of a consistent filter; the exact mode's lies inside it.
TEST(CooperativeEkfSlam, TheSeedFormulationIsOverConfidentWhereOneSightingExtendsMany) {
  constexpr int kTrials = 300;
  double nees_extended = 0.0, nees_exact = 0.0;
  for (int trial = 0; trial < kTrials; ++trial) {
    Fleet fleet;
    fleet.rng = Rng::ForStream(17, trial);
    fleet.truth = {Pose2(0, 0, 0), Pose2(200, 0, 3.0)};
    std::vector<int> all;
    for (int l = 0; l < 8; ++l) {
      fleet.landmarks.push_back({60.0 + 10.0 * l, l % 2 ? 50.0 : -50.0});
      all.push_back(l);
    }
    // Both starts known to 0.1 m: a coarse v-v sighting tells little of b, and placing b's
    // landmarks through it is what costs the seed's formulation.
    const Eigen::Matrix3d start_cov = Eigen::Vector3d(0.01, 0.01, 1e-6).asDiagonal();
    std::vector<Pose2> guesses = fleet.truth;
    for (Pose2& g : guesses) {
      const double dx = fleet.rng.Normal(0, 0.1), dy = fleet.rng.Normal(0, 0.1);
      g = Pose2(g.x() + dx, g.y() + dy, g.theta() + fleet.rng.Normal(0, 1e-3));
    }
    CooperativeEkfSlam extended = MakeFilter(CooperativeMode::kExtended, 2, 0);
    CooperativeEkfSlam exact = MakeFilter(CooperativeMode::kExact, 2, 0);
    extended.Reset(guesses, start_cov);
    exact.Reset(guesses, start_cov);
    fleet.sigma_range_m = 2.0;  // a coarse v-v sensor
    fleet.sigma_bearing_rad = 0.01;
    const FleetScan vv = fleet.Scan(0, {}, {1});
    fleet.sigma_range_m = 0.5;
    fleet.sigma_bearing_rad = 0.005;
    const FleetScan b_scan = fleet.Scan(1, all, {});
    for (CooperativeEkfSlam* f : {&extended, &exact}) {
      f->Update(vv);
      f->Update(b_scan);
    }
    // 20 m ahead on odometry good to 4 m.
    Control u(2);
    u << 20.0, 0.0;
    fleet.truth[0] = UnicycleModel().Move(fleet.truth[0], u, 1.0);
    ControlCovariance Q = ControlCovariance::Zero(2, 2);
    Q(0, 0) = 16.0;
    Q(1, 1) = 1e-8;
    Control noisy = u;
    noisy[0] += fleet.rng.Normal(0.0, 4.0);
    noisy[1] += fleet.rng.Normal(0.0, 1e-4);
    const FleetScan a_scan = fleet.Scan(0, all, {});
    for (CooperativeEkfSlam* f : {&extended, &exact}) {
      f->Predict(0, noisy, 1.0, &Q);
      f->Update(a_scan);
    }
    EXPECT_EQ(extended.NumLandmarks(), 8);
    const auto nees = [&](const CooperativeEkfSlam& f) {
      Eigen::Vector3d e = f.PoseOf(0).vector() - fleet.truth[0].vector();
      e[2] = WrapAngle(e[2]);
      return e.dot(f.PoseCovarianceOf(0).ldlt().solve(e));
    };
    nees_extended += nees(extended) / kTrials;
    nees_exact += nees(exact) / kTrials;
  }
  const ChiSquareBand band = AneesBand(kTrials, 3);
  EXPECT_TRUE(band.Contains(nees_exact)) << nees_exact << " not in [" << band.lo << ", "
                                         << band.hi << "]";
  EXPECT_GT(nees_extended, 2.0 * band.hi) << nees_extended;
}

// The counts in metrics.json: a sighting that updates its landmark, one the gate drops, and the
// new landmark, which is neither.

}  // namespace
}  // namespace slamkit
