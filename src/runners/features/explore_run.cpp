#include "slamkit/runners/features/explore_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>

#include "slamkit/core/angle.hpp"
#include "slamkit/eval/errors.hpp"
#include "slamkit/features/line_extraction.hpp"
#include "slamkit/runners/features/feature_exploration.hpp"

namespace slamkit {
namespace {

// The feature EKF with its pose covariance kept at every step, for the NEES.
class RecordingSlam final : public ExplorationSlam {
 public:
  RecordingSlam(const FeatureSlamParams& params, const Pose2& start)
      : slam_(params, start), diagnostics_(params.ekf.selection_diagnostics) {}
  void Step(const Pose2& delta, const LaserScan& scan) override {
    slam_.Step(delta, scan);
    covariances_.push_back(slam_.PoseCovariance());
    if (diagnostics_) accuracy_.push_back(slam_.slam().LastSelectionStats().accuracy());
    // The returns placed from the estimate just made: what the map is built from.
    AppendWorldPoints(scan, slam_.Estimate(), std::numeric_limits<double>::infinity(),
                      &scan_points_);
  }
  Pose2 Estimate() const override { return slam_.Estimate(); }
  double ModelledCostS() const override { return slam_.ModelledCostS(); }
  const FeatureEkfSlam& slam() const { return slam_.slam(); }
  const std::vector<Eigen::Matrix3d>& covariances() const { return covariances_; }
  const std::vector<std::optional<double>>& accuracy() const { return accuracy_; }
  std::vector<Eigen::Vector2d> TakeScanPoints() { return std::move(scan_points_); }

 private:
  FeatureExplorationSlam slam_;
  bool diagnostics_;
  std::vector<Eigen::Matrix3d> covariances_;
  std::vector<std::optional<double>> accuracy_;
  std::vector<Eigen::Vector2d> scan_points_;
};

std::vector<double> PoseNees(const ExplorationRun& run,
                             const std::vector<Eigen::Matrix3d>& covariances) {
  std::vector<double> nees;
  for (std::size_t i = 1; i < run.truth.size(); ++i) {  // step 0 is the known start
    const Pose2& x = run.truth[i].pose;
    const Pose2& e = run.estimate[i].pose;
    const Eigen::Vector3d d(e.x() - x.x(), e.y() - x.y(), WrapAngle(e.theta() - x.theta()));
    nees.push_back(Nees(d, covariances[i]));
  }
  return nees;
}

}  // namespace

void AppendWorldPoints(const LaserScan& scan, const Pose2& robot, double max_range_m,
                       std::vector<Eigen::Vector2d>* points) {
  const Pose2 laser = robot.Compose(scan.laser_offset);
  for (const BeamPoint& b : ScanToBeamPoints(scan, max_range_m)) {
    points->push_back(laser.TransformFrom(b.p));
  }
}

std::vector<MappedLine> MappedLines(const FeatureEkfSlam& slam) {
  std::vector<MappedLine> lines;
  for (int i = 0; i < slam.NumLines(); ++i) {
    if (slam.LineMergedInto(i) >= 0) continue;
    const LineExtent& extent = slam.LineExtentOf(i);
    lines.push_back({slam.Line(i), slam.LineCovariance(i), extent.start_m, extent.end_m});
  }
  return lines;
}

std::vector<Eigen::Vector2d> MappedCorners(const FeatureEkfSlam& slam) {
  std::vector<Eigen::Vector2d> corners;
  for (int i = 0; i < slam.NumCorners(); ++i) corners.push_back(slam.CornerPosition(i));
  return corners;
}

ExploreResult RunFeatureExploration(const FloorPlan& plan, const ExplorationConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  RecordingSlam slam(config.slam, config.start);
  Rng rng(config.seed);
  ExploreResult out;
  out.run = RunExploration(plan, config.start, slam, config.run, rng);
  out.nees = PoseNees(out.run, slam.covariances());
  out.accuracy = slam.accuracy();
  out.scan_points = slam.TakeScanPoints();
  out.lines = MappedLines(slam.slam());
  out.corners = MappedCorners(slam.slam());
  out.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace slamkit
