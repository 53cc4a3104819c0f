#include "slamkit/runners/features/feature_log_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "common/input_error.hpp"
#include "common/synthetic_room.hpp"
#include "common/temp_dir.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/runners/features/feature_log_config.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

// configs/features.yaml documents the defaults: loading it onto other values gives exactly
// FeatureLogParams{}.
TEST(FeatureLogConfig, TheShippedFileHoldsEveryDefault) {
  FeatureLogParams other;
  other.selection = SelectionKind::kAll;
  other.covariance.k_max = 9;
  other.odometry_noise.str = 0.7;
  other.extraction.sigma_range_m = 0.3;
  other.ekf.lines.overlap_margin_m = 2.0;
  other.ekf.corners.gate_chi2 = 3.0;
  other.max_wall_time_s = 5.0;
  const FeatureLogParams loaded =
      LoadFeatureLogConfig(fs::path(SLAMKIT_SOURCE_DIR) / "configs" / "features.yaml", other);
  EXPECT_EQ(FeatureLogParamsJson(loaded), FeatureLogParamsJson(FeatureLogParams{}));
}

class FeatureLogConfigFile : public testing::TempDirTest {};

// The effective parameters in metrics.json, written back as YAML (JSON is YAML), reproduce them,
// infinities (null) included.
TEST_F(FeatureLogConfigFile, TheParametersJsonLoadsBackToTheSameParameters) {
  FeatureLogParams p;
  p.selection = SelectionKind::kEntropyFast;
  p.entropy.min_gain_nats = 0.3;
  p.odometry_noise.srt = 0.25;
  p.extraction.max_usable_range_m = std::numeric_limits<double>::infinity();
  p.extraction.min_points = 9;
  p.ekf.lines.min_new_length_m = 0.7;
  p.max_wall_time_s = 12.5;
  p.accuracy_ratio_every = 0;
  const fs::path path = WriteFile("params.yaml", FeatureLogParamsJson(p).dump(2));
  EXPECT_EQ(FeatureLogParamsJson(LoadFeatureLogConfig(path)), FeatureLogParamsJson(p));
  EXPECT_TRUE(std::isinf(LoadFeatureLogConfig(path).extraction.max_usable_range_m));
}

TEST_F(FeatureLogConfigFile, MistakesNameTheFileLineAndKey) {
  struct Case {
    std::string yaml, part;
  };
  const Case cases[] = {
      {"selection:\n  policy: best\n", "f.yaml:2: key 'selection.policy': expected one of all"},
      {"odometry:\n  srr: -1\n", "f.yaml:2: key 'odometry.srr': must be >= 0"},
      {"extraction: {sigma_range_m: 0}\n", "key 'extraction.sigma_range_m': must be > 0"},
      {"extraction: {min_points: 1}\n", "key 'extraction.min_points'"},
      {"lines: {gate: 3}\n", "gate"},
      {"linear_update_m: fast\n", "f.yaml:1: key 'linear_update_m'"},
      {"particles: 30\n", "particles"}};
  for (const Case& c : cases) {
    const std::string message =
        testing::InputErrorOf([&] { LoadFeatureLogConfig(WriteFile("f.yaml", c.yaml)); });
    EXPECT_NE(message.find(c.part), std::string::npos) << c.yaml << "\n" << message;
  }
}

// Two laps of a circle in the test room, scanned with 1 cm noise, with odometry whose heading
// drifts by 0.4° per step: the log a run reads.
CarmenLog DriftingRoomLog(int steps) {
  CarmenLog log;
  Rng rng(5);
  Pose2 odometry;
  Pose2 previous(2.0, 0.0, M_PI / 2.0);
  for (int k = 0; k < steps; ++k) {
    const double a = 4.0 * M_PI * k / steps;
    const Pose2 truth(2.0 * std::cos(a), 2.0 * std::sin(a), a + M_PI / 2.0);
    const Pose2 delta = previous.Between(truth);
    odometry = odometry.Compose(Pose2(delta.x(), delta.y(), delta.theta() + 0.007));
    previous = truth;
    LaserScan scan = testing::RoomScan(truth, 0.1 * k, odometry);
    for (float& r : scan.ranges_m) {
      if (r < scan.max_range_m) r += static_cast<float>(rng.Normal(0.0, 0.01));
    }
    scan.logged_pose = truth;
    log.scans.push_back(scan);
  }
  return log;
}

double FinalError(const Trajectory& path, const CarmenLog& log) {
  // Both start at the first scan: the estimate at the origin, the truth at its logged pose.
  const Pose2 to_origin = log.scans.front().logged_pose.Inverse();
  const Pose2 truth = to_origin.Compose(log.scans.back().logged_pose);
  return (path.back().pose.translation() - truth.translation()).norm();
}

TEST(RunFeatureSlamOnLog, LinesAndCornersHoldTheRoomWhereTheOdometryDrifts) {
  const CarmenLog log = DriftingRoomLog(400);
  const FeatureLogResult r = RunFeatureSlamOnLog(log, FeatureLogParams{});
  ASSERT_EQ(r.trajectory.size(), log.scans.size());
  Trajectory odometry;
  for (const LaserScan& s : log.scans) odometry.push_back({s.t_s, s.odometry});
  const double odometry_error = FinalError(odometry, log);
  ASSERT_GT(odometry_error, 1.0);  // the drift is there to be corrected
  EXPECT_LT(FinalError(r.trajectory, log), 0.1 * odometry_error);
  EXPECT_GT(r.lines_seen.matched, 2 * r.updates);  // a room shows several walls per scan
  EXPECT_GE(r.lines.size(), 6u);
  EXPECT_LE(r.lines.size(), 20u);  // 12 walls, some seen as two pieces: not one per sighting
  EXPECT_FALSE(r.accuracy.empty());
  for (double a : r.accuracy) {
    EXPECT_GT(a, 0.0);
    EXPECT_LE(a, 1.0 + 1e-9);
  }
}

TEST(RunFeatureSlamOnLog, AWallTimeLimitKeepsWhatWasComputed) {
  const CarmenLog log = DriftingRoomLog(100);
  FeatureLogParams p;
  p.max_wall_time_s = 1e-9;
  const FeatureLogResult r = RunFeatureSlamOnLog(log, p);
  EXPECT_TRUE(r.stopped_early);
  EXPECT_GE(r.trajectory.size(), 1u);
  EXPECT_LT(r.trajectory.size(), log.scans.size());
  EXPECT_EQ(FeatureLogMetrics(r, p, nullptr, nullptr)["scans_reached"], r.trajectory.size());
}

TEST(RunFeatureSlamOnLog, ALogWithoutScansIsAnInputError) {
  const std::string message =
      testing::InputErrorOf([] { RunFeatureSlamOnLog(CarmenLog{}, FeatureLogParams{}); });
  EXPECT_NE(message.find("no laser scan"), std::string::npos) << message;
}

}  // namespace
}  // namespace slamkit
