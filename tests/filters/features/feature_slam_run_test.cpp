// The feature EKF-SLAM of SPEC S1 (lines and corners) on a simulated laser run through the
// shipped office world: better than odometry, consistent (pose NEES), one landmark per wall.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <set>

#include "slamkit/features/scan_features.hpp"
#include "slamkit/filters/features/feature_ekf_slam.hpp"
#include "slamkit/filters/selection/selection_policies.hpp"
#include "slamkit/io/floor_plan_reader.hpp"
#include "slamkit/io/waypoints_reader.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/sim/laser_sim.hpp"

namespace slamkit {
namespace {

struct Run {
  FloorPlan plan;
  GridSimRun sim;
  int walls_in_view = 0;
};

int WallsInView(const FloorPlan& plan, const GridSimRun& sim);

// The first part of office_route.txt, short enough for a sanitizer build: along the corridor,
// into the room south of x = 12, back and on along the corridor to x = 28 (about 39 m).
const Run& OfficeRun() {
  static const Run run = [] {
    Run r;
    const std::string dir = std::string(SLAMKIT_SOURCE_DIR) + "/examples/plans/";
    r.plan = FloorPlan{ReadFloorPlanFile(dir + "office.txt")};
    GridSimParams params;
    params.route.waypoints_m = ReadWaypoints(dir + "office_route.txt");
    params.route.waypoints_m.resize(5);
    params.route.switch_distance_m = 0.5;
    params.speed_mps = 1.0;  // 0.1 m between scans: half the scans of the default 0.5 m/s
    params.laser.beams = 181;
    params.laser.range_limit_m = 10.0;
    params.laser.sigma_range_m = 0.01;
    Rng rng(2026);
    const Pose2 start(params.route.waypoints_m[0].x(), params.route.waypoints_m[0].y(), 0.0);
    r.sim = SimulateGridRun(r.plan, params, start, rng);
    r.walls_in_view = WallsInView(r.plan, r.sim);
    return r;
  }();
  return run;
}

struct Result {
  double final_error_m = 0.0;
  double odometry_error_m = 0.0;
  double mean_error_m = 0.0;  // of the position, over all scans
  double odometry_mean_error_m = 0.0;
  double mean_nees = 0.0;
  double seconds = 0.0;
  double mean_accuracy = 0.0;  // SPEC S1, Eq. 24, over the steps with matches
  long matched = 0;            // sightings matched, and of them applied, over the run
  long applied = 0;
  int lines = 0;
  int merged = 0;
  int corners = 0;
  int duplicates = 0;
  int walls_in_view = 0;
};

// Walls that at least 1 m of true beam end points fell on (within 5 cm), from every second scan:
// the walls a line landmark can have been started from (LineAssociationParams::min_new_length_m).
// Plain arithmetic: it runs 10⁷ times, in a sanitizer build too.
int WallsInView(const FloorPlan& plan, const GridSimRun& sim) {
  std::vector<std::pair<double, double>> span(plan.walls.size(), {1e9, -1e9});
  for (std::size_t k = 0; k < sim.scans.size(); k += 2) {
    const LaserScan& scan = sim.scans[k];
    const Pose2 x = sim.truth[k].pose.Compose(scan.laser_offset);
    for (int beam = 0; beam < static_cast<int>(scan.ranges_m.size()); ++beam) {
      if (!scan.IsReturn(beam) || !(scan.ranges_m[beam] < 10.0)) continue;
      const double a = x.theta() + scan.BeamAngle(beam), r = scan.ranges_m[beam];
      const double px = x.x() + r * std::cos(a), py = x.y() + r * std::sin(a);
      for (std::size_t w = 0; w < plan.walls.size(); ++w) {
        const double x0 = plan.walls[w].first.x(), y0 = plan.walls[w].first.y();
        const double dx = plan.walls[w].second.x() - x0, dy = plan.walls[w].second.y() - y0;
        const double length = std::hypot(dx, dy);
        const double along = (dx * (px - x0) + dy * (py - y0)) / length;
        const double across = (dx * (py - y0) - dy * (px - x0)) / length;
        if (along < 0.0 || along > length || std::abs(across) > 0.05) continue;
        span[w] = {std::min(span[w].first, along), std::max(span[w].second, along)};
      }
    }
  }
  int n = 0;
  for (const auto& [lo, hi] : span) n += hi - lo >= 1.0;
  return n;
}

// Line landmarks of the same wall: (ρ, α) within 0.15 m and 0.05 rad and extents overlapping.
int Duplicates(const FeatureEkfSlam& slam) {
  int n = 0;
  for (int i = 0; i < slam.NumLines(); ++i) {
    for (int j = i + 1; j < slam.NumLines(); ++j) {
      if (slam.LineMergedInto(i) >= 0 || slam.LineMergedInto(j) >= 0) continue;
      const PolarLine a = slam.Line(i), b = slam.Line(j);
      if (std::abs(a.rho_m - b.rho_m) > 0.15 ||
          std::abs(WrapAngle(a.alpha_rad - b.alpha_rad)) > 0.05) {
        continue;
      }
      const LineExtent &ea = slam.LineExtentOf(i), &eb = slam.LineExtentOf(j);
      if (SegmentOverlapM(ea.start_m, ea.end_m, eb.start_m, eb.end_m, a.alpha_rad) > 0.0) ++n;
    }
  }
  return n;
}

Result RunFeatureSlam(std::unique_ptr<SelectionPolicy> policy) {
  const Run& run = OfficeRun();
  OdometryParams odometry;  // GridSimParams: σ_v dt = 5 mm, σ_ω dt = 2 mrad per step, inflated
  odometry.sigma_xy_m = 0.0075;
  odometry.sigma_theta_rad = 0.003;
  FeatureEkfSlamParams params;
  params.selection_diagnostics = true;  // the accuracy ratio of SPEC S1, Eq. 24, for the record
  FeatureEkfSlam slam(params, std::make_unique<OdometryModel>(odometry), std::move(policy));
  slam.Reset(run.sim.truth[0].pose);
  LineExtractionParams extraction;
  extraction.max_usable_range_m = 10.0;
  extraction.sigma_range_m = 0.01;
  Result r;
  int accuracy_steps = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < run.sim.scans.size(); ++k) {
    const LaserScan& scan = run.sim.scans[k];
    if (k > 0) {
      const Pose2 u = run.sim.scans[k - 1].odometry.Between(scan.odometry);
      slam.Predict(u.vector(), 0.1);
    }
    slam.Update(ToRobotFrame(ExtractFeatures(scan, extraction), scan.laser_offset));
    const SelectionStats& stats = slam.LastSelectionStats();
    r.matched += stats.candidates;
    r.applied += stats.applied;
    if (const auto accuracy = stats.accuracy()) {
      r.mean_accuracy += *accuracy;
      ++accuracy_steps;
    }
    const Pose2& truth = run.sim.truth[k].pose;
    Eigen::Vector3d e = slam.pose().vector() - truth.vector();
    e[2] = WrapAngle(e[2]);
    if (k > 0) r.mean_nees += e.dot(slam.PoseCovariance().ldlt().solve(e));
    r.mean_error_m += e.head<2>().norm();
    r.odometry_mean_error_m += (scan.odometry.translation() - truth.translation()).norm();
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  slam.CheckOutputHealth();
  r.mean_nees /= static_cast<double>(run.sim.scans.size() - 1);
  r.mean_error_m /= static_cast<double>(run.sim.scans.size());
  r.mean_accuracy /= std::max(accuracy_steps, 1);
  r.odometry_mean_error_m /= static_cast<double>(run.sim.scans.size());
  const Pose2& truth = run.sim.truth.back().pose;
  r.final_error_m = (slam.pose().translation() - truth.translation()).norm();
  r.odometry_error_m = (run.sim.scans.back().odometry.translation() - truth.translation()).norm();
  r.lines = slam.NumActiveLines();
  r.merged = slam.NumLines() - r.lines;
  r.corners = slam.NumCorners();
  r.duplicates = Duplicates(slam);
  r.walls_in_view = run.walls_in_view;
  std::printf(
      "mean error %.3f m (odometry %.3f m), final error %.3f m (odometry %.3f m), "
      "mean NEES %.2f, %d lines for %d walls in view (%d merged), %d corners, %d duplicates, %zu "
      "scans in %.2f s\n",
      r.mean_error_m, r.odometry_mean_error_m, r.final_error_m, r.odometry_error_m, r.mean_nees,
      r.lines, r.walls_in_view, r.merged, r.corners, r.duplicates, run.sim.scans.size(), r.seconds);
  std::printf("%ld of %ld matched sightings applied, mean accuracy ratio %.3f\n", r.applied,
              r.matched, r.mean_accuracy);
  return r;
}

void ExpectGoodRun(const Result& r) {
  EXPECT_LT(r.final_error_m, 0.5 * r.odometry_error_m);
  EXPECT_LT(r.mean_error_m, 0.5 * r.odometry_mean_error_m);
  EXPECT_LT(r.mean_nees, 9.0) << "3 × the 3-dof expectation";
  EXPECT_LE(r.lines, 1.5 * r.walls_in_view);
  EXPECT_GE(r.lines, r.walls_in_view / 1.5);
  EXPECT_EQ(r.duplicates, 0);
}

TEST(FeatureEkfSlamRun, OfficeWithSelectAllBeatsOdometryConsistently) {
  const Result r = RunFeatureSlam(std::make_unique<SelectAll>());
  ExpectGoodRun(r);
  EXPECT_EQ(r.applied, r.matched);
}

TEST(FeatureEkfSlamRun, OfficeWithCovarianceSelectionBeatsOdometryConsistently) {
  CovarianceSelectionParams params;
  params.k_max = 3;
  const Result r = RunFeatureSlam(std::make_unique<SelectByCovariance>(params));
  ExpectGoodRun(r);
  EXPECT_LT(r.applied, r.matched) << "k_max = 3 should have dropped some sightings";
}

}  // namespace
}  // namespace slamkit
