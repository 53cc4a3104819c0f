// The iSAM runner's noise options, its scoring against a reference with indistinguishable ids
// merged, and its configuration file.
#include "slamkit/runners/landmark/isam_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"
#include "slamkit/runners/landmark/isam_config.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

PointObservation Sighting(const Pose2& from, const Eigen::Vector2d& tree, LandmarkId id) {
  PointObservation obs;
  obs.z = from.TransformTo(tree);
  obs.R = 0.01 * Eigen::Matrix2d::Identity();
  obs.id = id;
  return obs;
}

// A straight drive of 1 m steps past `trees`; each step sights the trees within 8 m, with the
// file id `id_of(tree index, step)`.
template <typename IdOf>
IsamLog DrivePast(const std::vector<Eigen::Vector2d>& trees, int steps, IdOf id_of) {
  IsamLog log;
  auto sightings = [&](const Pose2& pose, int step) {
    std::vector<PointObservation> out;
    for (std::size_t t = 0; t < trees.size(); ++t) {
      if ((trees[t] - pose.translation()).norm() < 8.0) {
        out.push_back(Sighting(pose, trees[t], id_of(int(t), step)));
      }
    }
    return out;
  };
  log.initial_sightings = sightings(Pose2(), 0);
  for (int k = 1; k <= steps; ++k) {
    IsamStep step;
    step.pose_index = k;
    step.odometry = Eigen::Vector3d(1.0, 0.0, 0.0);
    step.odometry_covariance = Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal();
    step.sightings = sightings(Pose2(double(k), 0.0, 0.0), k);
    log.steps.push_back(step);
  }
  return log;
}

// Tree 1 is given id 10 until step 6 and id 11 after (the writer lost it and started it again);
// trees 0 and 2 stand 0.3 m apart but are sighted together, so they are two.
TEST(IndistinguishableReferenceIds, MergesATreeTheFileSplitAndNothingElse) {
  const std::vector<Eigen::Vector2d> trees = {{3.0, 2.0}, {8.0, -2.0}, {3.0, 2.3}, {14.0, 3.0}};
  const IsamLog log = DrivePast(trees, 16, [](int tree, int step) -> LandmarkId {
    return tree == 1 ? (step <= 6 ? 10 : 11) : tree;
  });
  IsamRunParams params;
  const auto groups = IndistinguishableReferenceIds(log, params);
  ASSERT_EQ(groups.size(), 1u);
  EXPECT_EQ(groups[0], (std::vector<LandmarkId>{10, 11}));

  params.ekf.association_method = AssociationMethod::kKnown;
  const IsamRunResult known = RunEkfSlamOnIsam(log, params);
  EXPECT_EQ(known.association_agreement, 1.0);
  // Nearest neighbour keeps tree 1 as one landmark: scored one-to-one against the split ids it
  // loses the smaller part, against the merged reference nothing.
  params.ekf.association_method = AssociationMethod::kNearestNeighbour;
  const IsamRunResult nn = RunEkfSlamOnIsam(log, params);
  EXPECT_LT(nn.association_agreement, 0.95);
  EXPECT_EQ(nn.association_agreement_merged, 1.0);
  EXPECT_EQ(nn.map.landmarks.size(), trees.size());
}

// A log whose odometry under-reports a turn: the file's tiny constant covariance rejects the
// trees once the heading is off, the motion-proportional noise keeps them.
TEST(IsamRunNoise, MotionProportionalOdometryNoiseAbsorbsAnUnderReportedTurn) {
  std::vector<Eigen::Vector2d> trees;
  for (int i = 0; i < 12; ++i) trees.push_back({2.0 + 1.5 * i, i % 2 ? 3.0 : -3.0});
  IsamLog log = DrivePast(trees, 16, [](int tree, int) -> LandmarkId { return tree; });
  // The true path is straight; the odometry says the car turned 0.05 rad at each of steps 3–5.
  for (int k = 2; k < 5; ++k) log.steps[k].odometry.z() = 0.05;
  IsamRunParams params;
  const IsamRunResult tight = RunEkfSlamOnIsam(log, params);
  params.odometry_noise = {0.02, 0.02, 0.01, 0.5};
  const IsamRunResult loose = RunEkfSlamOnIsam(log, params);
  EXPECT_GT(tight.map.landmarks.size(), trees.size());
  EXPECT_EQ(loose.map.landmarks.size(), trees.size());
  EXPECT_GT(loose.association_agreement, tight.association_agreement);
}

// Odometry that turns 0.03 rad right per metre where the car drives straight. A run with loose
// noise estimates that drift from its own path; configured, the drift lets the file's tight
// covariance map each tree once, where uncalibrated it starts duplicates.
TEST(IsamRunHeadingDrift, TheFittedDriftCalibratesTheOdometry) {
  std::vector<Eigen::Vector2d> trees;
  for (int i = 0; i < 24; ++i) trees.push_back({2.0 + 1.5 * i, i % 2 ? 3.0 : -3.0});
  IsamLog log = DrivePast(trees, 36, [](int tree, int) -> LandmarkId { return tree; });
  for (IsamStep& step : log.steps) step.odometry.z() = -0.03;
  IsamRunParams params;
  params.heading_drift_fit.window_steps = 6;
  params.odometry_noise = {0.02, 0.02, 0.02, 0.5};
  const IsamRunResult loose = RunEkfSlamOnIsam(log, params);
  ASSERT_TRUE(loose.odometry_heading_drift.has_value());
  EXPECT_EQ(loose.odometry_heading_drift->windows, 6);
  EXPECT_NEAR(loose.odometry_heading_drift->drift_rad_per_m, 0.03, 0.006);
  EXPECT_LT(loose.odometry_heading_drift->rms_after_rad,
            0.2 * loose.odometry_heading_drift->rms_before_rad);

  params.odometry_noise = {0.0, 0.0, 0.0, 0.0};
  const IsamRunResult tight = RunEkfSlamOnIsam(log, params);
  params.odometry_heading_drift_rad_per_m = loose.odometry_heading_drift->drift_rad_per_m;
  const IsamRunResult calibrated = RunEkfSlamOnIsam(log, params);
  EXPECT_GT(tight.map.landmarks.size(), trees.size());
  EXPECT_EQ(calibrated.map.landmarks.size(), trees.size());
  EXPECT_EQ(calibrated.association_agreement, 1.0);
  // The fit is of the file's odometry, whatever the run added: the same drift again.
  EXPECT_NEAR(calibrated.odometry_heading_drift->drift_rad_per_m, 0.03, 0.006);
}

// The log above, whose odometry bends a straight drive: least squares with the file's ids and
// loose noise gives the straight path back (the sightings are exact), where dead reckoning
// ends 1.8 m off; a run is scored against it.
TEST(IsamSmoothedReference, StraightensThePathTheOdometryBends) {
  std::vector<Eigen::Vector2d> trees;
  for (int i = 0; i < 12; ++i) trees.push_back({2.0 + 1.5 * i, i % 2 ? 3.0 : -3.0});
  IsamLog log = DrivePast(trees, 16, [](int tree, int) -> LandmarkId { return tree; });
  for (int k = 2; k < 5; ++k) log.steps[k].odometry.z() = 0.05;
  IsamRunParams params;
  params.odometry_noise = {0.02, 0.02, 0.01, 0.5};
  const IsamSmoothedReference ref = SmoothIsamLog(log, params);
  ASSERT_EQ(ref.path.size(), log.steps.size() + 1);
  Pose2 dead_reckoning;
  for (const IsamStep& step : log.steps) {
    dead_reckoning = dead_reckoning.Compose(Pose2(step.odometry.x(), 0.0, step.odometry.z()));
  }
  EXPECT_GT(std::abs(dead_reckoning.y()), 1.5);
  for (std::size_t k = 0; k < ref.path.size(); ++k) {
    const Eigen::Vector2d truth(double(k), 0.0);
    EXPECT_LT((ref.path[k].pose.translation() - truth).norm(), 0.05) << k;
  }
  ASSERT_EQ(ref.landmarks.size(), trees.size());
  for (const auto& [id, p] : ref.landmarks) EXPECT_LT((p - trees[id]).norm(), 0.05) << id;

  const IsamRunResult run = RunEkfSlamOnIsam(log, params);
  ASSERT_TRUE(run.smoothed_reference.has_value());
  EXPECT_EQ(run.smoothed_reference->landmarks_compared, static_cast<int>(trees.size()));
  EXPECT_LT(run.smoothed_reference->map_rmse_m, 0.1);
  EXPECT_EQ(run.smoothed_reference->ate.count, static_cast<int>(ref.path.size()));
  // A sighting the smoother cannot weigh (a singular covariance) costs the comparison only.
  IsamLog bad = log;
  bad.steps[3].sightings[0].R.setZero();
  const IsamRunResult kept = RunEkfSlamOnIsam(bad, params);
  EXPECT_FALSE(kept.smoothed_reference.has_value());
  EXPECT_NE(kept.smoothed_reference_failure.find("not positive definite"), std::string::npos);
  EXPECT_EQ(kept.estimate.size(), ref.path.size());
  params.compare_with_smoothed_reference = false;
  EXPECT_FALSE(RunEkfSlamOnIsam(log, params).smoothed_reference.has_value());
}

class IsamConfigFile : public testing::TempDirTest {};

TEST_F(IsamConfigFile, ReadsEveryKeyAndWritesItBack) {
  const fs::path path = WriteFile("vp.yaml",
                                  "association: jcbb\ngate_chi2: 8\nnew_landmark_chi2: 20\n"
                                  "max_joint_tests: 500\n"
                                  "odometry: {covariance_scale: 2, srr: 0.1, srt: 0.2, str: 0.3, "
                                  "stt: 0.4, heading_drift_rad_per_m: -0.002}\n"
                                  "sightings: {covariance_scale: 3, sigma_range_m: 0.25, "
                                  "sigma_bearing_deg: 2}\n"
                                  "score_against_merged_reference: false\n"
                                  "compare_with_smoothed_reference: false\n"
                                  "fastslam: {new_landmark_test: mahalanobis, gate_chi2: 15, "
                                  "delayed_sampling: true, window_max_landmarks: 25}\n");
  const IsamRunParams p = LoadIsamConfig(path);
  EXPECT_EQ(p.fastslam.new_landmark_test, NewLandmarkTest::kMahalanobis);
  EXPECT_EQ(p.fastslam.gate_chi2, 15.0);
  EXPECT_FALSE(p.fastslam.new_landmark_chi2.has_value());
  EXPECT_TRUE(p.fastslam.delayed_sampling);
  EXPECT_EQ(p.fastslam.window_max_landmarks, 25);
  EXPECT_FALSE(p.compare_with_smoothed_reference);
  EXPECT_EQ(p.ekf.association_method, AssociationMethod::kJointCompatibility);
  EXPECT_EQ(p.ekf.association.gate_chi2, 8.0);
  EXPECT_EQ(p.ekf.jcbb.max_joint_tests, 500);
  EXPECT_EQ(p.odometry_covariance_scale, 2.0);
  EXPECT_EQ(p.odometry_noise.stt, 0.4);
  EXPECT_EQ(p.odometry_heading_drift_rad_per_m, -0.002);
  EXPECT_EQ(p.sighting_covariance_scale, 3.0);
  EXPECT_NEAR(p.sighting_sigma_bearing_rad, 2.0 * M_PI / 180.0, 1e-15);
  EXPECT_FALSE(p.score_against_merged_reference);
  const fs::path back = WriteFile("back.yaml", IsamParamsJson(p).dump());
  EXPECT_EQ(IsamParamsJson(LoadIsamConfig(back)), IsamParamsJson(p));
}

TEST_F(IsamConfigFile, MistakesNameTheFileLineAndKey) {
  const auto error = [&](const std::string& text) {
    const fs::path path = WriteFile("bad.yaml", text);
    return testing::InputErrorOf([&] { LoadIsamConfig(path); });
  };
  EXPECT_NE(error("association: mle\n").find("bad.yaml:1"), std::string::npos);
  EXPECT_NE(error("association: mle\n").find("association"), std::string::npos);
  EXPECT_NE(error("gate_chi2: 9\nodometry: {stt: -1}\n").find("odometry.stt"), std::string::npos);
  EXPECT_NE(error("gate_chi2: 20\n").find("new_landmark_chi2 must be >= gate_chi2"),
            std::string::npos);
  EXPECT_NE(error("sightings: {sigma_range_m: 0.3}\n").find("sigma_range_m"), std::string::npos);
  EXPECT_NE(error("odometry: {srq: 1}\n").find("srq"), std::string::npos);
  EXPECT_NE(error("odometry: {heading_drift_rad_per_m: .nan}\n")
                .find("odometry.heading_drift_rad_per_m"),
            std::string::npos);
  EXPECT_NE(error("fastslam: {new_landmark_test: p0}\n").find("fastslam.new_landmark_test"),
            std::string::npos);
  EXPECT_NE(error("fastslam: {window_max_landmarks: 0}\n").find("fastslam.window_max_landmarks"),
            std::string::npos);
  EXPECT_NE(error("fastslam: {delayed_sampling: 2}\n").find("fastslam.delayed_sampling"),
            std::string::npos);
  EXPECT_NE(error("fastslam: {gate_chi2: 20, new_landmark_chi2: 10}\n")
                .find("new_landmark_chi2 must be >= gate_chi2"),
            std::string::npos);
}

TEST(IsamConfig, TheShippedVictoriaParkFileLoads) {
  const IsamRunParams p =
      LoadIsamConfig(fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "victoria_park.yaml");
  EXPECT_EQ(p.ekf.association_method, AssociationMethod::kJointCompatibility);
  EXPECT_GT(p.sighting_sigma_range_m, 0.0);
  EXPECT_TRUE(p.fastslam.delayed_sampling);
}

}  // namespace
}  // namespace slamkit
