// The Monte Carlo harness runs on any LandmarkSlamFilter: here on toy filters defined in the
// test, which get NEES/ANEES, RMSE, association scoring and map error without any harness code
// of their own (as FastSLAM and the cooperative EKF will).
#include <atomic>
#include <cstdio>
#include <cmath>
#include <map>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "slamkit/filters/landmark_slam.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/runners/landmark/monte_carlo.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"
#include "slamkit/sim/world.hpp"

namespace slamkit {
namespace {

ScenarioConfig ShortScenario() {
  return LoadScenario(std::string(SLAMKIT_SOURCE_DIR) + "/configs/short.yaml");
}

// Dead reckoning through the motion model, its covariance propagated with the model's Q scaled
// by `q_scale` (1: honest, 0.01: over-confident). Every sighting becomes a new landmark, placed
// by the inverse sensor model from the dead-reckoned pose. Counts the observations it received
// that carried a landmark id, so the test can see whether the truth leaked in.
class DeadReckoningFilter final : public LandmarkSlamFilter {
 public:
  DeadReckoningFilter(const ScenarioParams& scenario, double q_scale,
                      std::atomic<int>* ids_received)
      : motion_(MakeMotionModel(scenario.vehicle)),
        sensor_(scenario.sensor),
        q_scale_(q_scale),
        ids_received_(ids_received) {}

  void Reset(const Pose2& pose, const Eigen::Matrix3d& pose_cov) override {
    pose_ = pose;
    P_ = pose_cov;
    map_.landmarks.clear();
  }
  void Predict(const Control& u, double dt_s, const ControlCovariance* control_noise) override {
    Eigen::Matrix3d J_x;
    ControlJacobian J_u;
    pose_ = motion_->Move(pose_, u, dt_s, &J_x, &J_u);
    const ControlCovariance Q = control_noise ? *control_noise : motion_->Noise(u, dt_s);
    P_ = J_x * P_ * J_x.transpose() + q_scale_ * (J_u * Q * J_u.transpose());
  }
  std::vector<AssociationDecision> Update(
      std::span<const PointObservation> observations) override {
    std::vector<AssociationDecision> decisions;
    for (const PointObservation& obs : observations) {
      if (obs.id != kNoLandmark) ++*ids_received_;
      MappedLandmark l;
      l.position_m = sensor_.Invert(pose_, obs.z);
      l.covariance = Eigen::Matrix2d::Identity();
      map_.landmarks.push_back(l);
      AssociationDecision d;
      d.kind = AssociationDecision::Kind::kNew;
      d.landmark = static_cast<int>(map_.landmarks.size()) - 1;
      decisions.push_back(d);
    }
    return decisions;
  }
  Pose2 PoseEstimate() const override { return pose_; }
  Eigen::Matrix3d PoseCovariance() const override { return P_; }
  int NumLandmarks() const override { return static_cast<int>(map_.landmarks.size()); }
  LandmarkMap Map() const override { return map_; }

 private:
  std::unique_ptr<MotionModel> motion_;
  RangeBearingModel sensor_;
  double q_scale_;
  std::atomic<int>* ids_received_;
  Pose2 pose_;
  Eigen::Matrix3d P_ = Eigen::Matrix3d::Zero();
  LandmarkMap map_;
};

LandmarkFilterFactory DeadReckoning(const ScenarioParams& scenario, double q_scale,
                                    std::atomic<int>* ids_received) {
  return [&scenario, q_scale, ids_received] {
    return std::make_unique<DeadReckoningFilter>(scenario, q_scale, ids_received);
  };
}

MonteCarloParams Params(bool known_association) {
  MonteCarloParams params;
  params.runs = 20;
  params.seed = 5;
  params.threads = 2;
  params.known_association = known_association;
  return params;
}

TEST(LandmarkHarness, OverConfidentToyFilterGetsAneesFarOutsideTheBand) {
  const ScenarioConfig config = ShortScenario();
  std::atomic<int> ids(0);
  const MonteCarloResult honest =
      RunMonteCarlo(config.scenario, DeadReckoning(config.scenario, 1.0, &ids), Params(false));
  const MonteCarloResult overconfident =
      RunMonteCarlo(config.scenario, DeadReckoning(config.scenario, 0.01, &ids), Params(false));
  std::printf("dead reckoning: ANEES %.3f (%.0f%% of steps in [%.3f, %.3f]); Q x 0.01: %.3f "
              "(%.0f%%)\n",
              honest.anees_mean, 100.0 * honest.anees_fraction_in_band, honest.band.lo,
              honest.band.hi, overconfident.anees_mean,
              100.0 * overconfident.anees_fraction_in_band);
  // Same inputs, same estimates: only the covariance differs, so NEES scales by 1/0.01.
  EXPECT_EQ(honest.rmse.position_m, overconfident.rmse.position_m);
  EXPECT_NEAR(overconfident.anees_mean / honest.anees_mean, 100.0, 1.0);
  EXPECT_GT(overconfident.anees_mean, 10.0 * overconfident.band.hi);
  EXPECT_LT(overconfident.anees_fraction_in_band, 0.05);
  // Honest dead reckoning is consistent (its covariance is the linearised but correct one), and
  // the harness says so with the per-step band over its 20 runs.
  EXPECT_GE(honest.anees_fraction_in_band, 0.9);
  EXPECT_EQ(ids.load(), 0);  // unknown association: no true id reached the filter
}

TEST(LandmarkHarness, ToyFilterGetsRmseAssociationAndMapErrorFromTheInterface) {
  const ScenarioConfig config = ShortScenario();
  std::atomic<int> ids(0);
  const MonteCarloResult toy =
      RunMonteCarlo(config.scenario, DeadReckoning(config.scenario, 1.0, &ids), Params(false));
  const MonteCarloResult ekf = RunMonteCarlo(config.scenario, EkfSlamFactory(config),
                                             Params(config.ekf.known_association()));
  // Dead reckoning drifts; EKF-SLAM with the same inputs does not.
  EXPECT_GT(toy.rmse.position_m, 3.0 * ekf.rmse.position_m);
  EXPECT_GT(toy.map_rmse_mean_m, 3.0 * ekf.map_rmse_mean_m);
  // It never matches: every sighting made a landmark, none was scored as a match.
  const AssociationScore& a = toy.association;
  EXPECT_EQ(a.sightings, ekf.association.sightings);  // the same simulated runs
  EXPECT_EQ(a.created, a.sightings);
  EXPECT_EQ(a.matched, 0);
  EXPECT_EQ(a.dropped, 0);
  EXPECT_GT(a.matchable, a.sightings / 2);  // the landmarks were in its map, found or not
  EXPECT_EQ(a.Recall(), 0.0);
  EXPECT_DOUBLE_EQ(toy.landmarks_mapped_mean, double(a.sightings) / toy.runs.size());
  // The harness named each landmark after the sighting that created it: each true landmark as
  // often as it was seen, so the map's ids tally with the sightings of run 0's truth.
  std::map<LandmarkId, int> per_id;
  for (const MappedLandmark& m : toy.runs[0].map.landmarks) ++per_id[m.source_id];
  EXPECT_EQ(per_id.count(kNoLandmark), 0u);
  EXPECT_EQ(per_id.size(), toy.world.landmarks.size());
  EXPECT_EQ(ids.load(), 0);
}

TEST(LandmarkHarness, TrueIdsReachTheFilterOnlyWithKnownAssociation) {
  const ScenarioConfig config = ShortScenario();
  std::atomic<int> ids(0);
  MonteCarloParams params = Params(false);
  params.runs = 2;
  const MonteCarloResult unknown =
      RunMonteCarlo(config.scenario, DeadReckoning(config.scenario, 1.0, &ids), params);
  EXPECT_EQ(ids.load(), 0);
  params.known_association = true;
  const MonteCarloResult known =
      RunMonteCarlo(config.scenario, DeadReckoning(config.scenario, 1.0, &ids), params);
  EXPECT_EQ(ids.load(), known.association.sightings);
  EXPECT_GT(ids.load(), 1000);
}

// A filter that breaks the interface's promise of one decision per observation.
class ForgetfulFilter final : public LandmarkSlamFilter {
 public:
  void Reset(const Pose2& pose, const Eigen::Matrix3d&) override { pose_ = pose; }
  void Predict(const Control&, double, const ControlCovariance*) override {}
  std::vector<AssociationDecision> Update(std::span<const PointObservation>) override {
    return {};
  }
  Pose2 PoseEstimate() const override { return pose_; }
  Eigen::Matrix3d PoseCovariance() const override { return Eigen::Matrix3d::Identity(); }
  int NumLandmarks() const override { return 0; }
  LandmarkMap Map() const override { return {}; }

 private:
  Pose2 pose_;
};

TEST(LandmarkHarness, FilterBreakingTheInterfaceIsReported) {
  const ScenarioConfig config = ShortScenario();
  MonteCarloParams params = Params(false);
  params.runs = 1;
  EXPECT_THROW(RunMonteCarlo(config.scenario,
                             [] { return std::make_unique<ForgetfulFilter>(); }, params),
               std::logic_error);
}

// The map history the viewer draws: between N and 2N snapshots spaced evenly over the run
// (thinned as the run grows), the final map last, each landmark named as in the final map; and
// taking it leaves the run as it was, bit for bit.
TEST(MonteCarlo, AMapHistoryIsEvenAndLeavesTheRunAsItWas) {
  ScenarioConfig c = ShortScenario();
  c.ekf.association_method = AssociationMethod::kNearestNeighbour;
  const LandmarkWorld world = MakeWorld(c.scenario.world);
  const auto run = [&](int snapshots) {
    Rng noise(3), order(1003);
    const SimRun sim = Simulate(c.scenario, world, noise, order);
    const auto filter = EkfSlamFactory(c)();
    return RunLandmarkFilter(*filter, sim, world, c.scenario.dt_s, false, snapshots);
  };
  const RunResult plain = run(0), kept = run(6);
  EXPECT_TRUE(plain.map_history.empty());
  ASSERT_EQ(kept.estimate.size(), plain.estimate.size());
  for (std::size_t k = 0; k < kept.estimate.size(); ++k) {
    ASSERT_EQ(kept.estimate[k].pose.vector(), plain.estimate[k].pose.vector()) << k;
  }
  const std::vector<LandmarkMapSnapshot>& h = kept.map_history;
  ASSERT_GE(h.size(), 6u + 1);
  ASSERT_LE(h.size(), 12u + 1);
  EXPECT_EQ(h.front().t_s, 0.0);
  EXPECT_EQ(h.back().t_s, kept.estimate.back().t_s);
  const double spacing = h[1].t_s - h[0].t_s;
  for (std::size_t i = 1; i + 1 < h.size(); ++i) {
    EXPECT_NEAR(h[i].t_s - h[i - 1].t_s, spacing, 1e-9) << i;
    EXPECT_LE(h[i - 1].map.landmarks.size(), h[i].map.landmarks.size());
  }
  ASSERT_EQ(h.back().map.landmarks.size(), kept.map.landmarks.size());
  for (std::size_t i = 0; i < kept.map.landmarks.size(); ++i) {
    EXPECT_EQ(h.back().map.landmarks[i].position_m, kept.map.landmarks[i].position_m);
    EXPECT_EQ(h.back().map.landmarks[i].source_id, kept.map.landmarks[i].source_id);
  }
  const std::size_t middle = h.size() / 2;
  for (std::size_t i = 0; i < h[middle].map.landmarks.size(); ++i) {
    EXPECT_EQ(h[middle].map.landmarks[i].source_id, kept.map.landmarks[i].source_id);
  }
}

}  // namespace
}  // namespace slamkit
