#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/maps/occupancy_image.hpp"

namespace slamkit {

// What the replay viewer shows of a run (`slamkit report DIR` gathers it from the folder).
struct ReportPath {
  std::string name;   // "estimate", "truth", "odometry", ...
  std::string color;  // a CSS colour
  Trajectory poses;
  // The position covariance at each pose (empty, or one per pose): the 2σ ellipse at the
  // slider's time.
  std::vector<Eigen::Matrix2d> covariances;
};

struct ReportLandmark {
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();
  std::optional<Eigen::Matrix2d> covariance;  // drawn as its 2σ ellipse
  bool estimated = true;                      // else a true landmark
};

// The estimated landmarks as the filter held them at time t_s (a run's map history).
struct ReportMapSnapshot {
  double t_s = 0.0;
  std::vector<ReportLandmark> landmarks;
};

struct ReportSeries {
  std::string name;  // "ANEES", "position RMSE [m]", ...
  std::vector<double> t_s;
  std::vector<double> values;
  std::optional<std::pair<double, double>> band;  // drawn as two lines (ANEES's χ² band)
};

struct ReportData {
  std::string title;
  nlohmann::json metrics;           // the run's metrics.json (shown as a table)
  std::vector<ReportPath> paths;    // the first is the one the time slider follows
  std::optional<OccupancyImage> map;
  std::vector<ReportLandmark> landmarks;
  // When given, the estimated landmarks drawn at the slider's time are the last snapshot's at or
  // before it (the final map's are drawn with no history).
  std::vector<ReportMapSnapshot> map_history;
  std::vector<ReportSeries> series;
};

struct HtmlReportParams {
  // Longer paths and series are decimated (evenly, the last point kept), and larger maps shrunk
  // by whole factors (a block's darkest pixel, so walls stay), so that a report stays a few MB.
  std::size_t max_path_points = 4000;
  std::size_t max_series_points = 4000;
  std::size_t max_map_pixels = 1'500'000;
  // Snapshots of the map history are dropped evenly (the last kept) beyond this many landmarks
  // in all.
  std::size_t max_history_landmarks = 200'000;
};

// One self-contained HTML page (no network: the data and the script inline): the map with the
// paths growing over time (a slider and a play button; `#t=F` in the address starts at fraction
// F), the first path's pose and its 2σ ellipse at the slider's time (its size in the element
// `pose-sigma`), the landmarks with their 2σ ellipses (from the map history at the slider's time
// when there is one; their count in `landmarks-shown`), the series over time with a cursor at
// the slider's time, and the metrics as a table (cell ids `m-KEY`, nested keys joined by dots).
std::string HtmlReport(const ReportData& data, const HtmlReportParams& params = {});

}  // namespace slamkit
