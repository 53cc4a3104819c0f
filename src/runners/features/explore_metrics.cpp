#include <algorithm>
#include <numeric>

#include "slamkit/eval/consistency.hpp"
#include "slamkit/runners/features/explore_run.hpp"

namespace slamkit {
namespace {

const char* ModeName(ExplorerMode mode) {
  switch (mode) {
    case ExplorerMode::kTracking: return "tracking";
    case ExplorerMode::kAvoiding: return "avoiding";
    case ExplorerMode::kTurning: return "turning";
    case ExplorerMode::kReturning: return "returning";
    case ExplorerMode::kDone: return "done";
  }
  return "unknown";
}

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

nlohmann::json ExploreMetrics(const ExploreResult& r, const ExplorationConfig& config) {
  const std::vector<double>& t = r.run.slam_time_s;
  const auto [mean_error, final_error] = PositionErrors(r.run.estimate, r.run.truth);
  const auto [odo_mean, odo_final] = PositionErrors(r.run.odometry, r.run.truth);
  // One run's steps are not independent samples: the band is that of their mean as if they
  // were, a yardstick rather than a test.
  const ChiSquareBand band = AneesBand(std::max<int>(1, int(r.nees.size())), 3);
  return {{"params", ExplorationConfigJson(config)},
          {"steps", t.size()},
          {"elapsed_s", r.run.elapsed_s},
          {"slam_time_total_s", std::accumulate(t.begin(), t.end(), 0.0)},
          {"slam_time_max_s", t.empty() ? 0.0 : *std::max_element(t.begin(), t.end())},
          {"open_loop_time_s", r.run.open_loop_time_s},
          {"mean_nees", Mean(r.nees)},
          {"nees_band", {band.lo, band.hi}},
          {"mean_error_m", mean_error},
          {"final_error_m", final_error},
          {"odometry_mean_error_m", odo_mean},
          {"odometry_final_error_m", odo_final},
          {"lines", r.lines.size()},
          {"corners", r.corners.size()},
          {"final_mode", ModeName(r.run.final_mode)},
          {"wall_time_s", r.wall_time_s}};
}

}  // namespace slamkit
