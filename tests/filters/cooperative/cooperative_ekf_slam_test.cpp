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
