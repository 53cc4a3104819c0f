#include "slamkit/runners/features/exploration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <vector>

#include "slamkit/io/floor_plan_reader.hpp"

namespace slamkit {
namespace {

// Dead reckoning with a fixed modelled cost: the exploration loop's SLAM at its simplest.
class OdometryOnlySlam final : public ExplorationSlam {
 public:
  explicit OdometryOnlySlam(double cost_s) : cost_s_(cost_s) {}
  void Step(const Pose2& odometry_delta, const LaserScan& scan) override {
    pose_ = pose_.Compose(odometry_delta);
    ++steps_;
    if (keep_scans_) scans_.push_back(scan);
  }
  Pose2 Estimate() const override { return pose_; }
  double ModelledCostS() const override { return cost_s_; }
  int steps() const { return steps_; }
  void Start(const Pose2& p) { pose_ = p; }
  // Keeps every scan it is handed: the loop gives the explorer the same scan.
  void KeepScans() { keep_scans_ = true; }
  const std::vector<LaserScan>& scans() const { return scans_; }

 private:
  double cost_s_;
  Pose2 pose_;
  int steps_ = 0;
  bool keep_scans_ = false;
  std::vector<LaserScan> scans_;
};

FloorPlan Office() {
  return FloorPlan{ReadFloorPlanFile(std::filesystem::path(SLAMKIT_SOURCE_DIR) /
                                     "examples/plans/office.txt")};
}

ExplorationRun Explore(double cost_s, std::uint64_t seed, double max_time_s,
                       OdometryOnlySlam* recorder = nullptr) {
  ExplorationParams params;
  params.max_time_s = max_time_s;
  OdometryOnlySlam own(cost_s);
  OdometryOnlySlam& slam = recorder != nullptr ? *recorder : own;
  const Pose2 start(4.0, 15.0, 0.0);
  slam.Start(start);
  Rng rng(seed);
  return RunExploration(Office(), start, slam, params, rng);
}

// SPEC S1: a step costing t holds the previous command for ⌈t / 0.1⌉ · 0.1 s.
TEST(RunExploration, TheSlamTimeHoldsThePreviousCommand) {
  const ExplorationRun slow = Explore(0.25, 1, 60.0);
  const int steps = static_cast<int>(slow.slam_time_s.size());
  ASSERT_GT(steps, 10);
  EXPECT_NEAR(slow.open_loop_time_s, 0.3 * steps, 1e-9);
  // A step is 0.3 s held plus the 0.1 s period of the new command.
  EXPECT_NEAR(slow.truth[1].t_s - slow.truth[0].t_s, 0.4, 1e-12);
  const ExplorationRun instant = Explore(0.0, 1, 60.0);
  EXPECT_EQ(instant.open_loop_time_s, 0.0);
  EXPECT_NEAR(instant.truth[1].t_s - instant.truth[0].t_s, 0.1, 1e-12);
}

TEST(RunExploration, TheSameSeedGivesTheSamePathInTheModelledMode) {
  const ExplorationRun a = Explore(0.05, 7, 40.0);
  const ExplorationRun b = Explore(0.05, 7, 40.0);
  ASSERT_EQ(a.truth.size(), b.truth.size());
  for (std::size_t i = 0; i < a.truth.size(); ++i) {
    ASSERT_EQ(a.truth[i].pose.translation(), b.truth[i].pose.translation()) << "step " << i;
  }
  const ExplorationRun other = Explore(0.05, 8, 40.0);
  EXPECT_NE(a.odometry.back().pose.translation(), other.odometry.back().pose.translation());
}

// The robot goes where the SLAM says: the estimate, not the truth, drives it. Dead reckoning
// drifts from the truth exactly as the odometry does.
TEST(RunExploration, TheEstimateIsTheSlamsAndTheRobotExplores) {
  const ExplorationRun run = Explore(0.0, 3, 120.0);
  ASSERT_FALSE(run.truth.empty());
  for (std::size_t i = 0; i < run.truth.size(); ++i) {
    ASSERT_LT((run.estimate[i].pose.translation() - run.odometry[i].pose.translation()).norm(),
              1e-9);
  }
  EXPECT_GT((run.truth.back().pose.translation() - run.truth.front().pose.translation()).norm(),
            5.0);
  // The odometry noise is there: the SLAM is not handed the truth.
  EXPECT_GT((run.truth.back().pose.translation() - run.odometry.back().pose.translation()).norm(),
            0.01);
}

// The commands a fresh explorer gives for a run's (estimate, scan, time) inputs, each scan's
// logged pose (what a log may carry beside the odometry) set by `logged(i)` and each estimate
// moved by `shift`.
std::vector<Control> Replay(const ExplorationRun& run, const std::vector<LaserScan>& scans,
                            const std::function<Pose2(std::size_t)>& logged,
                            const Pose2& shift = Pose2()) {
  FrontierExplorer explorer(ExplorationParams{}.explorer);
  std::vector<Control> commands;
  for (std::size_t i = 0; i < run.commands.size(); ++i) {
    LaserScan scan = scans[i];
    scan.logged_pose = logged(i);
    const StampedPose& at = run.planner_pose[i];
    commands.push_back(explorer.Step(at.pose.Compose(shift), scan, at.t_s));
  }
  return commands;
}

// Issue 10: the planner never uses the truth. Its inputs replayed give the run's commands again;
// with the true pose, perturbed, put where the scan could carry it, still the same commands;
// with the estimate perturbed instead, other commands (so the replay does feed the explorer).
TEST(RunExploration, ThePlannerNeverReadsTheTruth) {
  OdometryOnlySlam recorder(0.05);
  recorder.KeepScans();
  const ExplorationRun run = Explore(0.05, 5, 90.0, &recorder);
  ASSERT_EQ(run.commands.size(), run.truth.size());
  ASSERT_EQ(recorder.scans().size(), run.truth.size());
  ASSERT_GT(run.commands.size(), 100u);
  const auto none = [](std::size_t) { return Pose2(); };
  const auto perturbed_truth = [&run](std::size_t i) {
    return run.truth[i].pose.Compose(Pose2(0.7, -0.4, 0.5));
  };
  const std::vector<Control> again = Replay(run, recorder.scans(), none);
  const std::vector<Control> with_truth = Replay(run, recorder.scans(), perturbed_truth);
  for (std::size_t i = 0; i < run.commands.size(); ++i) {
    ASSERT_EQ(again[i], run.commands[i]) << "step " << i;
    ASSERT_EQ(with_truth[i], run.commands[i]) << "step " << i;
  }
  const std::vector<Control> shifted = Replay(run, recorder.scans(), none, Pose2(0.3, 0.2, 0.3));
  int differ = 0;
  for (std::size_t i = 0; i < run.commands.size(); ++i) differ += shifted[i] != run.commands[i];
  EXPECT_GT(differ, int(run.commands.size()) / 2);
}

}  // namespace
}  // namespace slamkit
