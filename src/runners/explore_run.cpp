#include "slamkit/runners/explore_run.hpp"

#include <algorithm>
#include <chrono>
#include <numeric>

#include "slamkit/core/angle.hpp"
#include "slamkit/eval/errors.hpp"
#include "slamkit/runners/feature_exploration.hpp"

namespace slamkit {
namespace {

// The feature EKF with its pose covariance kept at every step, for the NEES.
class RecordingSlam final : public ExplorationSlam {
 public:
  RecordingSlam(const FeatureSlamParams& params, const Pose2& start) : slam_(params, start) {}
  void Step(const Pose2& delta, const LaserScan& scan) override {
    slam_.Step(delta, scan);
    covariances_.push_back(slam_.PoseCovariance());
  }
  Pose2 Estimate() const override { return slam_.Estimate(); }
  double ModelledCostS() const override { return slam_.ModelledCostS(); }
  const FeatureEkfSlam& slam() const { return slam_.slam(); }
  const std::vector<Eigen::Matrix3d>& covariances() const { return covariances_; }

 private:
  FeatureExplorationSlam slam_;
  std::vector<Eigen::Matrix3d> covariances_;
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

void CollectMap(const FeatureEkfSlam& slam, ExploreResult* out) {
  for (int i = 0; i < slam.NumLines(); ++i) {
    if (slam.LineMergedInto(i) >= 0) continue;
    const LineExtent& extent = slam.LineExtentOf(i);
    out->lines.push_back({slam.Line(i), slam.LineCovariance(i), extent.start_m, extent.end_m});
  }
  for (int i = 0; i < slam.NumCorners(); ++i) out->corners.push_back(slam.CornerPosition(i));
}

}  // namespace

ExploreResult RunFeatureExploration(const FloorPlan& plan, const ExplorationConfig& config) {
  const auto start = std::chrono::steady_clock::now();
  RecordingSlam slam(config.slam, config.start);
  Rng rng(config.seed);
  ExploreResult out;
  out.run = RunExploration(plan, config.start, slam, config.run, rng);
  out.nees = PoseNees(out.run, slam.covariances());
  CollectMap(slam.slam(), &out);
  out.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace slamkit
