// The state-health checks of the filters (issue 8): each fails when it should, on the state the
// filter really holds, and passes on healthy runs.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "common/landmark_inputs.hpp"
#include "common/synthetic_room.hpp"
#include "filters/landmark_circuit.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/filters/grid/rbpf_grid_slam.hpp"
#include "slamkit/filters/particles/particle_set.hpp"
#include "slamkit/models/relative_point.hpp"

namespace slamkit {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// What `f` threw as NumericalError ("" if nothing).
template <class F>
std::string NumericalFailure(F&& f) {
  try {
    f();
  } catch (const NumericalError& e) {
    return e.what();
  }
  return "";
}

bool Contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

StateHealthParams Health(StateHealthMode mode) {
  StateHealthParams health;
  health.mode = mode;
  health.psd_interval_per_entry = 0.0;  // the PSD test at every update
  return health;
}

EkfSlam MakeSlam(StateHealthMode mode, bool known_association = true) {
  EkfSlamParams params;
  params.health = Health(mode);
  if (known_association) params.association_method = AssociationMethod::kKnown;
  return EkfSlam(params, std::make_unique<OdometryModel>(), std::make_unique<RelativePointModel>());
}

using testing::Odo;

PointObservation Sighting(double x, double y, LandmarkId id) {
  PointObservation obs;
  obs.z << x, y;
  obs.R = 0.01 * Eigen::Matrix2d::Identity();
  obs.id = id;
  return obs;
}

// A direct observation of point block `point` (H = I on it) with zero innovation and noise r I.
Linearisation PointObservationOf(int point, double r) {
  Linearisation obs;
  obs.innovation = BlockVector::Zero(2);
  obs.H.Add(point, Eigen::Matrix2d::Identity());
  obs.R = r * Eigen::Matrix2d::Identity();
  return obs;
}

TEST(BlockEkfHealth, ChecksTheEffectiveCovarianceWithoutApplyingThePendingDowndate) {
  BlockEkf ekf(8);
  const int point = ekf.RegisterKind({2, {}, false});
  ekf.AddBlock(kPoseKind, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * 0.1);
  const int l = ekf.AddBlock(point, Eigen::Vector2d(3, 4), Eigen::Matrix2d::Identity());
  const StateHealthParams health = Health(StateHealthMode::kEveryUpdate);
  ASSERT_TRUE(ekf.Update(PointObservationOf(l, 0.5)));
  ASSERT_TRUE(ekf.HasPendingDowndate());
  EXPECT_EQ(NumericalFailure([&] { ekf.CheckHealth(health, true, "healthy"); }), "");
  EXPECT_TRUE(ekf.HasPendingDowndate());  // the check only reads
  // A negative "noise" that leaves S positive over-corrects: P_ll = I − I (0.5 I)⁻¹ I = −I. The
  // stored triangle is still healthy; only the deferred factor U holds the damage.
  BlockEkf broken(8);
  broken.RegisterKind({2, {}, false});
  broken.AddBlock(kPoseKind, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * 0.1);
  broken.AddBlock(point, Eigen::Vector2d(3, 4), Eigen::Matrix2d::Identity());
  ASSERT_TRUE(broken.Update(PointObservationOf(l, -0.5)));
  const std::string failure = NumericalFailure([&] { broken.CheckHealth(health, true, "U"); });
  EXPECT_TRUE(Contains(failure, "U: covariance is not positive semi-definite")) << failure;
  EXPECT_TRUE(Contains(failure, "smallest eigenvalue -1")) << failure;
  EXPECT_TRUE(broken.HasPendingDowndate());
}

TEST(BlockEkfHealth, NonFiniteInnovationReachesTheMeanAndIsCaught) {
  BlockEkf ekf(8);
  const int point = ekf.RegisterKind({2, {}, false});
  ekf.AddBlock(kPoseKind, Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity() * 0.1);
  const int l = ekf.AddBlock(point, Eigen::Vector2d(3, 4), Eigen::Matrix2d::Identity());
  Linearisation obs = PointObservationOf(l, 0.5);
  obs.innovation[1] = kNaN;
  ASSERT_TRUE(ekf.Update(obs));
  const std::string failure = NumericalFailure(
      [&] { ekf.CheckHealth(Health(StateHealthMode::kAtOutput), false, "after it"); });
  EXPECT_EQ(failure, "after it: mean entry 0 is nan");  // 0 · NaN in the pose rows of K
}

// A full simulated EKF-SLAM run (nearest-neighbour association, landmarks added and re-observed)
// with every check at every update, PSD included.
TEST(EkfSlamHealth, SimulatedRunPassesEveryUpdateChecks) {
  const OdometryParams odometry{.sigma_xy_m = 0.01, .sigma_theta_rad = 0.002};
  const RangeBearingParams sensor{.max_range_m = 8.0};
  testing::LandmarkCircuit circuit(12, 5, odometry, sensor);
  EkfSlamParams params;
  params.health = Health(StateHealthMode::kEveryUpdate);
  EkfSlam slam(params, std::make_unique<OdometryModel>(odometry),
               std::make_unique<RangeBearingModel>(sensor));
  slam.Reset(circuit.truth());
  std::vector<PointObservation> sightings;
  for (int k = 0; k < 400; ++k) {  // 1.3 laps
    slam.Predict(circuit.Step(), 0.1);
    circuit.Sight(sightings);
    for (PointObservation& s : sightings) s.id = kNoLandmark;
    ASSERT_NO_THROW(slam.Update(sightings)) << "step " << k;
  }
  EXPECT_NO_THROW(slam.CheckOutputHealth());
  EXPECT_GE(slam.NumLandmarks(), 12);
  EXPECT_LT((slam.pose().translation() - circuit.truth().translation()).norm(), 1.0);
}

// Issue 8 item 7: an odometry of 1e308 is finite, passes validation and overflows the
// covariance in the prediction; the check names the step instead of letting NaN reach a map.
TEST(EkfSlamHealth, OverflowingOdometryIsCaughtAtThePrediction) {
  EkfSlam slam = MakeSlam(StateHealthMode::kEveryUpdate);
  slam.Reset(Pose2(), Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  slam.Predict(Odo(1.0, 0.0, 0.1), 0.0);
  const std::string failure = NumericalFailure([&] { slam.Predict(Odo(1e308, 0.0, 0.0), 0.0); });
  EXPECT_EQ(failure,
            "EkfSlam after prediction 2 (update 0, 0 landmarks): covariance entry (0, 0) is inf");
}

// The same for a LANDMARK of 1e308 (the iSAM reader bounds magnitudes now; the filter must not
// rely on it): in Release the check at output catches what the run produced.
TEST(EkfSlamHealth, OverflowingSightingIsCaughtAtOutputAndAfterTheUpdate) {
  for (const StateHealthMode mode : {StateHealthMode::kAtOutput, StateHealthMode::kEveryUpdate}) {
    EkfSlam slam = MakeSlam(mode);
    slam.Reset(Pose2(), Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
    slam.Update(std::vector{Sighting(2.0, 1.0, 0)});
    slam.Predict(Odo(1.0, 0.0, 0.1), 0.0);
    const std::vector<PointObservation> huge = {Sighting(1e308, 0.0, 1)};
    std::string failure = NumericalFailure([&] {
      slam.Update(huge);
      slam.Predict(Odo(1.0, 0.0, 0.1), 0.0);
      slam.Update(std::vector{Sighting(1.0, 1.0, 0), Sighting(1e308, 0.0, 1)});
      slam.CheckOutputHealth();
    });
    if (mode == StateHealthMode::kAtOutput) {
      // By then the overflow has spread into the mean.
      EXPECT_EQ(failure,
                "EkfSlam at output (update 3, prediction 2, 2 landmarks): mean entry 0 is nan");
    } else {
      EXPECT_EQ(failure, "EkfSlam after update 2 (prediction 1, 2 landmarks): covariance entry "
                         "(5, 5) is inf");
    }
  }
}

// UpdateLandmark() skips Update()'s input validation: a NaN sighting reaches the mean, and the
// next check says so.
TEST(EkfSlamHealth, NanPastTheValidationIsCaught) {
  EkfSlam slam = MakeSlam(StateHealthMode::kEveryUpdate);
  slam.Reset(Pose2(), Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  slam.Update(std::vector{Sighting(2.0, 1.0, 0)});
  slam.UpdateLandmark(0, Sighting(kNaN, 1.0, 0));
  const std::string at_output = NumericalFailure([&] { slam.CheckOutputHealth(); });
  EXPECT_EQ(at_output,
            "EkfSlam at output (update 1, prediction 0, 1 landmarks): mean entry 0 is nan");
  EXPECT_EQ(NumericalFailure([&] { slam.Update({}); }),
            "EkfSlam after update 2 (prediction 0, 1 landmarks): mean entry 0 is nan");
}

TEST(EkfSlamHealth, NonFiniteControlIsRejectedBeforeAnyChange) {
  EkfSlam slam = MakeSlam(StateHealthMode::kEveryUpdate);
  slam.Reset(Pose2(1, 2, 0.3), Eigen::Matrix3d::Identity() * 0.01);
  const Eigen::VectorXd x = slam.State();
  const Eigen::MatrixXd P = slam.Covariance();
  EXPECT_THROW(slam.Predict(Odo(kNaN, 0.0, 0.0), 0.1), std::invalid_argument);
  EXPECT_THROW(slam.Predict(Odo(1.0, 0.0, 0.0), kNaN), std::invalid_argument);
  const ControlCovariance q = ControlCovariance::Identity(3, 3) * kNaN;
  EXPECT_THROW(slam.Predict(Odo(1.0, 0.0, 0.0), 0.1, &q), std::invalid_argument);
  EXPECT_THROW(slam.Update(std::vector{Sighting(kNaN, 0.0, 0)}), std::invalid_argument);
  EXPECT_EQ(slam.State(), x);
  EXPECT_EQ(slam.Covariance(), P);
}

TEST(EkfSlamHealth, OffChecksNothing) {
  EkfSlam slam = MakeSlam(StateHealthMode::kOff);
  slam.Update(std::vector{Sighting(2.0, 1.0, 0)});
  slam.UpdateLandmark(0, Sighting(kNaN, 1.0, 0));
  EXPECT_NO_THROW(slam.Update({}));
  EXPECT_NO_THROW(slam.CheckOutputHealth());
}

TEST(ParticleHealth, LogWeightsFiniteOrRuledOut) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_NO_THROW(CheckLogWeights(std::vector{-3.0, -inf, 0.5}, 0.1, "log-weight", "u"));
  EXPECT_NO_THROW(CheckLogWeights(std::vector<double>{}, 1.0, "log-weight", "u"));
  const auto failure = [](std::vector<double> w) {
    return NumericalFailure([&] { CheckLogWeights(w, 1.0, "log-weight", "update 3"); });
  };
  EXPECT_EQ(failure({0.0, 1.0, kNaN}), "update 3: particle 2's log-weight is nan");
  EXPECT_EQ(failure({inf, 1.0}), "update 3: particle 0's log-weight is inf");
  EXPECT_EQ(failure({-inf, -inf}), "update 3: every particle's log-weight is -inf");
  const std::string bad_gain =
      NumericalFailure([] { CheckLogWeights(std::vector{0.0, 1.0}, kNaN, "log-weight", "u"); });
  EXPECT_EQ(bad_gain, "u: the normalised log-weights sum to nan");
}

TEST(ParticleHealth, ParticleSetChecksBothWeights) {
  ParticleSet<int> set(4, 0);
  EXPECT_NO_THROW(set.CheckHealth(0.1, "ok"));
  set.AddLogWeight(1, kNaN);
  EXPECT_EQ(NumericalFailure([&] { set.CheckHealth(0.1, "now"); }),
            "now: particle 1's log-weight is nan");
}

// Resampling on NaN weights keeps copies of particle 0 with fresh weights: the evidence is gone
// from the weights, so the set remembers that a normalisation failed.
TEST(ParticleHealth, ParticleSetRemembersWeightsThatDidNotNormalise) {
  ParticleSet<int> set(4, 0);
  Rng rng(1);
  set.ResampleIfNeeded(1.0, {}, rng);
  set.AddLogWeight(2, kNaN);
  set.ResampleIfNeeded(1.0, {}, rng);
  set.Keep(std::vector{0, 0, 1, 3});  // drops particle 2 and its total
  EXPECT_EQ(NumericalFailure([&] { set.CheckHealth(1.0, "later"); }),
            "later: the weights did not normalise at resampling decision 2");
}

// A short run of the grid RBPF in the synthetic room (few particles: this runs under ASan).
std::vector<LaserScan> RoomRun() {
  std::vector<LaserScan> log;
  Pose2 pose(-5, -3, 0), odo;
  for (int k = 0; k < 8; ++k) {
    const Pose2 step(0.3, 0.0, 0.02);
    pose = pose.Compose(step);
    odo = odo.Compose(step);
    log.push_back(testing::RoomScan(pose, 0.1 * k, odo));
  }
  return log;
}

RbpfGridSlamParams SmallGridParams() {
  RbpfGridSlamParams params;
  params.particles = 4;
  params.linear_update_m = 0.5;
  params.health = Health(StateHealthMode::kEveryUpdate);
  return params;
}

TEST(GridSlamHealth, HealthyRunPassesAndABadWeightIsNamed) {
  RbpfGridSlam healthy(SmallGridParams());
  for (const LaserScan& scan : RoomRun()) ASSERT_NO_THROW(healthy.ProcessScan(scan));
  EXPECT_GT(healthy.updates(), 1);
  EXPECT_NO_THROW(healthy.CheckOutputHealth());

  RbpfGridSlam broken(SmallGridParams(), [](const GridWeightContext& c) {
    return c.particle == 2 ? kNaN : 0.0;
  });
  const std::string failure = NumericalFailure([&] {
    for (const LaserScan& scan : RoomRun()) broken.ProcessScan(scan);
  });
  EXPECT_EQ(failure, "RbpfGridSlam at update 1 (scan 2): particle 2's log-weight is nan");

  // At output only, as in Release: resampling has dropped the NaN by then, not the record of it.
  RbpfGridSlamParams at_output = SmallGridParams();
  at_output.health.mode = StateHealthMode::kAtOutput;
  RbpfGridSlam late(at_output, [](const GridWeightContext& c) {
    return c.particle == 2 ? kNaN : 0.0;
  });
  for (const LaserScan& scan : RoomRun()) ASSERT_NO_THROW(late.ProcessScan(scan));
  const std::string at_end = NumericalFailure([&] { late.CheckOutputHealth(); });
  EXPECT_TRUE(Contains(at_end, "RbpfGridSlam at output")) << at_end;
  EXPECT_TRUE(Contains(at_end, "nan") || Contains(at_end, "did not normalise")) << at_end;
}

}  // namespace
}  // namespace slamkit
