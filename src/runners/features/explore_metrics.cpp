#include <algorithm>
#include <numeric>
#include <tuple>

#include "slamkit/eval/consistency.hpp"
#include "slamkit/runners/features/explore_run.hpp"

namespace slamkit {
namespace {

double Mean(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

// Mean and final distance of `path` from the truth, pose by pose.
std::pair<double, double> PositionErrors(const Trajectory& path, const Trajectory& truth) {
  double sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    sum += (path[i].pose.translation() - truth[i].pose.translation()).norm();
  }
  const double last = truth.empty() ? 0.0
                                    : (path.back().pose.translation() -
                                       truth.back().pose.translation()).norm();
  return {truth.empty() ? 0.0 : sum / double(truth.size()), last};
}

}  // namespace

const char* ExplorerModeName(ExplorerMode mode) {
  switch (mode) {
    case ExplorerMode::kTracking: return "tracking";
    case ExplorerMode::kAvoiding: return "avoiding";
    case ExplorerMode::kTurning: return "turning";
    case ExplorerMode::kReturning: return "returning";
    case ExplorerMode::kDone: return "done";
  }
  return "unknown";
}

ExploreFigures ExploreFiguresOf(const ExploreResult& r) {
  const std::vector<double>& t = r.run.slam_time_s;
  ExploreFigures f;
  f.steps = static_cast<int>(t.size());
  f.elapsed_s = r.run.elapsed_s;
  f.slam_time_total_s = std::accumulate(t.begin(), t.end(), 0.0);
  f.slam_time_max_s = t.empty() ? 0.0 : *std::max_element(t.begin(), t.end());
  f.open_loop_time_s = r.run.open_loop_time_s;
  f.mean_nees = Mean(r.nees);
  // One run's steps are not independent samples: the band is that of their mean as if they
  // were, a yardstick rather than a test.
  f.nees_band = AneesBand(std::max<int>(1, int(r.nees.size())), 3);
  std::tie(f.mean_error_m, f.final_error_m) = PositionErrors(r.run.estimate, r.run.truth);
  std::tie(f.odometry_mean_error_m, f.odometry_final_error_m) =
      PositionErrors(r.run.odometry, r.run.truth);
  f.lines = static_cast<int>(r.lines.size());
  f.corners = static_cast<int>(r.corners.size());
  f.final_mode = r.run.final_mode;
  f.wall_time_s = r.wall_time_s;
  return f;
}

nlohmann::json ExploreFiguresJson(const ExploreFigures& f) {
  return {{"steps", f.steps},
          {"elapsed_s", f.elapsed_s},
          {"slam_time_total_s", f.slam_time_total_s},
          {"slam_time_max_s", f.slam_time_max_s},
          {"open_loop_time_s", f.open_loop_time_s},
          {"mean_nees", f.mean_nees},
          {"nees_band", {f.nees_band.lo, f.nees_band.hi}},
          {"mean_error_m", f.mean_error_m},
          {"final_error_m", f.final_error_m},
          {"odometry_mean_error_m", f.odometry_mean_error_m},
          {"odometry_final_error_m", f.odometry_final_error_m},
          {"lines", f.lines},
          {"corners", f.corners},
          {"final_mode", ExplorerModeName(f.final_mode)},
          {"wall_time_s", f.wall_time_s}};
}

nlohmann::json ExploreMetrics(const ExploreResult& r, const ExplorationConfig& config) {
  nlohmann::json j = ExploreFiguresJson(ExploreFiguresOf(r));
  j["params"] = ExplorationConfigJson(config);
  return j;
}

}  // namespace slamkit
