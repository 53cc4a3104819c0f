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

namespace slamkit {
namespace {

const UnicycleParams kMotion{0.05, 0.01};
const Eigen::Matrix2d kR = Eigen::Vector2d(0.1 * 0.1, 0.01 * 0.01).asDiagonal();

RangeBearingParams WideSensor() {
  RangeBearingParams sensor;
  sensor.max_range_m = 500.0;
  return sensor;
}

CooperativeEkfSlam MakeFilter(CooperativeMode mode, int vehicles, int self,
                              AssociationMethod association = AssociationMethod::kKnown,
                              JacobianEstimates jacobians = JacobianEstimates::kCurrent) {
  CooperativeEkfSlamParams p;
  p.mode = mode;
  p.ekf.association_method = association;
  p.ekf.jacobians = jacobians;
  const RangeBearingParams sensor = WideSensor();
  return CooperativeEkfSlam(p, vehicles, self, std::make_unique<UnicycleModel>(kMotion),
                            std::make_unique<RangeBearingModel>(sensor));
}

// A fleet driven and sensed with noise: the truth beside, the measurements for the filters.
struct Fleet {
  std::vector<Pose2> truth;
  std::vector<Eigen::Vector2d> landmarks;
  Rng rng{1};
  double sigma_range_m = 0.1;
  double sigma_bearing_rad = 0.01;
  Eigen::Matrix2d R() const {
    return Eigen::Vector2d(sigma_range_m * sigma_range_m, sigma_bearing_rad * sigma_bearing_rad)
        .asDiagonal();
  }

  Control Drive(int v, const Control& u, double dt) {
    truth[v] = UnicycleModel(kMotion).Move(truth[v], u, dt);
    Control noisy = u;
    noisy[0] += rng.Normal(0.0, kMotion.sigma_v_mps);
    noisy[1] += rng.Normal(0.0, kMotion.sigma_omega_radps);
    return noisy;
  }
  Eigen::Vector2d Noisy(const RangeBearing& z) {
    const double dr = rng.Normal(0.0, sigma_range_m);
    const double db = rng.Normal(0.0, sigma_bearing_rad);
    return {z.range_m + dr, WrapAngle(z.bearing_rad + db)};
  }
  // Vehicle v's scan of the landmarks `seen` (ids = their index) and of the vehicles `others`.
  FleetScan Scan(int v, std::vector<int> seen, std::vector<int> others, double t = 0.0) {
    FleetScan s;
    s.vehicle = v;
    s.t_s = t;
    for (const int l : seen) {
      s.landmarks.push_back({Noisy(PredictRangeBearing(truth[v], landmarks[l])), R(), l});
    }
    for (const int o : others) {
      s.vehicles.push_back({o, Noisy(PredictVehicleSighting(truth[v], truth[o])), R()});
    }
    return s;
  }
};

double PositionTrace(const CooperativeEkfSlam& f, int v) {
  return f.PoseCovarianceOf(v).topLeftCorner<2, 2>().trace();
}

TEST(CooperativeEkfSlam, TwoVehiclesThatNeverMeetAreTwoMonoFilters) {
  Fleet fleet;
  fleet.truth = {Pose2(0, 0, 0), Pose2(1000, 0, 1.0)};
  fleet.landmarks = {{5, 3}, {8, -2}, {1003, 4}, {1006, 1}};
  std::vector<Pose2> starts = fleet.truth;
  CooperativeEkfSlam exact = MakeFilter(CooperativeMode::kExact, 2, 0);
  CooperativeEkfSlam mono0 = MakeFilter(CooperativeMode::kMono, 2, 0);
  CooperativeEkfSlam mono1 = MakeFilter(CooperativeMode::kMono, 2, 1);
  for (CooperativeEkfSlam* f : {&exact, &mono0, &mono1}) f->Reset(starts);
  for (int k = 0; k < 20; ++k) {
    for (int v = 0; v < 2; ++v) {
      Control u(2);
      u << 1.0, 0.05;
      const Control noisy = fleet.Drive(v, u, 0.5);
      for (CooperativeEkfSlam* f : {&exact, &mono0, &mono1}) f->Predict(v, noisy, 0.5);
    }
    const FleetScan s0 = fleet.Scan(0, {0, 1}, {}), s1 = fleet.Scan(1, {2, 3}, {});
    for (CooperativeEkfSlam* f : {&exact, &mono0, &mono1}) {
      f->Update(s0);
      f->Update(s1);
    }
  }
  EXPECT_EQ(exact.NumLandmarks(), 4);
  EXPECT_EQ(mono0.NumLandmarks(), 2);
  for (const auto& [v, mono] : {std::pair{0, &mono0}, std::pair{1, &mono1}}) {
    EXPECT_LT((exact.PoseOf(v).vector() - mono->PoseOf(v).vector()).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((exact.PoseCovarianceOf(v) - mono->PoseCovarianceOf(v)).cwiseAbs().maxCoeff(),
              1e-12);
  }
}

// Mono is EkfSlam's filter on the vehicle's own inputs, with first-estimates Jacobians too: the
// prior pose each update linearises at and each landmark's first estimate are the same, so the
// two agree to rounding, and FEJ is not the textbook filter on the same inputs.
TEST(CooperativeEkfSlam, MonoWithFirstEstimatesIsEkfSlamWithFirstEstimates) {
  Fleet fleet;
  fleet.truth = {Pose2(0, 0, 0.3), Pose2(50, 0, 1.0)};
  fleet.landmarks = {{5, 3}, {8, -2}, {2, 6}, {-3, 4}, {9, 7}};
  EkfSlamParams ekf_params;
  ekf_params.association_method = AssociationMethod::kKnown;
  ekf_params.jacobians = JacobianEstimates::kFirstEstimates;
  EkfSlam reference(ekf_params, std::make_unique<UnicycleModel>(kMotion),
                    std::make_unique<RangeBearingModel>(WideSensor()));
  reference.Reset(fleet.truth[0]);
  CooperativeEkfSlam fej = MakeFilter(CooperativeMode::kMono, 2, 0, AssociationMethod::kKnown,
                                      JacobianEstimates::kFirstEstimates);
  CooperativeEkfSlam textbook = MakeFilter(CooperativeMode::kMono, 2, 0);
  for (CooperativeEkfSlam* f : {&fej, &textbook}) f->Reset(fleet.truth);
  for (int k = 0; k < 40; ++k) {
    Control u(2);
    u << 1.0, 0.3;
    const Control noisy = fleet.Drive(0, u, 0.5);
    reference.Predict(noisy, 0.5);
    for (CooperativeEkfSlam* f : {&fej, &textbook}) f->Predict(0, noisy, 0.5);
    const std::vector<int> seen = k < 5 ? std::vector<int>{0, 1} : std::vector<int>{0, 1, 2, 3, 4};
    const FleetScan scan = fleet.Scan(0, seen, {});
    reference.Update(scan.landmarks);
    for (CooperativeEkfSlam* f : {&fej, &textbook}) f->Update(scan);
  }
  ASSERT_EQ(fej.NumLandmarks(), reference.NumLandmarks());
  EXPECT_LT((fej.PoseOf(0).vector() - reference.pose().vector()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((fej.PoseCovarianceOf(0) - reference.PoseCovariance()).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_GT((fej.PoseCovarianceOf(0) - textbook.PoseCovarianceOf(0)).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(CooperativeEkfSlam, OneVehicleSightingReducesBothPositionCovariances) {
  for (const CooperativeMode mode : {CooperativeMode::kExact, CooperativeMode::kExtended}) {
    Fleet fleet;
    fleet.truth = {Pose2(0, 0, 0), Pose2(20, 5, 2.0)};
    CooperativeEkfSlam f = MakeFilter(mode, 2, 0);
    f.Reset(fleet.truth, Eigen::Vector3d(1.0, 1.0, 0.01).asDiagonal());
    const double before0 = PositionTrace(f, 0), before1 = PositionTrace(f, 1);
    f.Update(fleet.Scan(0, {}, {1}));
    EXPECT_LT(PositionTrace(f, 0), 0.99 * before0);
    EXPECT_LT(PositionTrace(f, 1), 0.99 * before1);
    EXPECT_EQ(f.counts().vehicle_updates, 1);
  }
}

// The exact filter of vehicle 0, fed every message, is the centralised filter, and both are the
// textbook dense EKF over [pose 0, pose 1, landmarks] fed the raw measurements once each.
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
TEST(CooperativeEkfSlam, CountsLandmarkUpdatesAndGatedSightings) {
  CooperativeEkfSlamParams p;
  p.mode = CooperativeMode::kMono;
  p.ekf.association_method = AssociationMethod::kKnown;
  CooperativeEkfSlam f(p, 2, 0, std::make_unique<UnicycleModel>(kMotion),
                       std::make_unique<RangeBearingModel>(WideSensor()),
                       std::make_unique<KnownAssociation>(13.8));
  const std::vector<Pose2> starts = {Pose2(), Pose2(5, 0, 0)};
  f.Reset(starts);
  FleetScan scan;
  scan.vehicle = 0;
  scan.landmarks.push_back({{10.0, 0.3}, kR, 7});
  f.Update(scan);
  scan.landmarks[0].z = {10.05, 0.301};
  f.Update(scan);
  scan.landmarks[0].z = {10.0, 0.8};  // 50 σ off in bearing
  f.Update(scan);
  scan.vehicle = 1;  // another vehicle's: Mono does not use it
  f.Update(scan);
  EXPECT_EQ(f.NumLandmarks(), 1);
  EXPECT_EQ(f.counts().landmark_updates, 1);
  EXPECT_EQ(f.counts().landmark_dropped, 1);
}

TEST(CooperativeEkfSlam, BadScansAreRejectedBeforeAnyChange) {
  CooperativeEkfSlam f = MakeFilter(CooperativeMode::kExact, 2, 0);
  const std::vector<Pose2> starts = {Pose2(), Pose2(5, 0, 0)};
  f.Reset(starts);
  FleetScan bad;
  bad.vehicle = 2;
  EXPECT_THROW(f.Update(bad), std::invalid_argument);
  bad.vehicle = 0;
  bad.vehicles.push_back({0, {1.0, 0.0}, kR});  // itself
  EXPECT_THROW(f.Update(bad), std::invalid_argument);
  bad.vehicles[0].target = 1;
  bad.vehicles[0].z.x() = NAN;
  EXPECT_THROW(f.Update(bad), std::invalid_argument);
  EXPECT_EQ(f.PoseOf(1).x(), 5.0);
  EXPECT_THROW(MakeFilter(CooperativeMode::kExtended, 2, -1), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit
