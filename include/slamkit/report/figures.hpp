#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/landmark_world.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/maps/occupancy_image.hpp"

namespace slamkit {

// What a map figure shows: the true and estimated paths, true landmarks and the estimated ones
// with their 2-sigma ellipses. Empty members are simply not drawn (a real data set has no truth).
struct PathFigureData {
  std::string title;
  Trajectory truth;
  Trajectory estimate;
  LandmarkWorld true_landmarks;
  LandmarkMap map;
  // Points to mark with large circles (SWSLAM's self-detected waypoints), listed in the legend
  // as `markers_label`.
  std::vector<Eigen::Vector2d> markers_m;
  std::string markers_label = "waypoints";
  double ellipse_sigma = 2.0;
  int width_px = 1200;
  int height_px = 1000;
};

// Writes the figure as PNG or SVG, chosen by the extension (".png" or ".svg", any case),
// atomically (temp file + rename). Throws std::invalid_argument for another extension and
// std::runtime_error naming `path` when it cannot be written; a failure leaves no file.
void WritePathFigure(const std::filesystem::path& path, const PathFigureData& data);

struct Segment2 {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
};
// A line-and-corner map: true walls (thin grey), raw scan points in the world (light dots;
// decimated when many), the mapped line segments (bold), corners (markers), and the paths.
// Empty members are not drawn.
struct LineMapFigureData {
  std::string title;
  std::vector<Segment2> walls;
  std::vector<Eigen::Vector2d> points;
  std::vector<Segment2> lines;
  std::vector<Eigen::Vector2d> corners;
  Trajectory truth;
  Trajectory estimate;
  Trajectory odometry;
  int width_px = 1200;
  int height_px = 1000;
};
// Formats and failures as for WritePathFigure (png/svg by extension, atomic, throws).
void WriteLineMapFigure(const std::filesystem::path& path, const LineMapFigureData& data);

// One curve of a series figure.
struct Series {
  std::string label;  // in the legend; empty: left out of it
  std::vector<double> x;
  std::vector<double> y;
  int colour = -1;     // index into a fixed palette (blue, red, green, magenta, cyan, black,
                       // grey; wraps); -1: the series' own index
  bool dashed = false;
  // 0: a line through the points; else the points alone, each drawn as this MathGL marker
  // ('o' circle, '+' plus, 'x' cross, 's' square, 'd' diamond), e.g. a map's landmarks.
  char marker = 0;
};

// Curves over a common x axis with a legend (e.g. accumulated SLAM time per selection policy).
struct SeriesFigureData {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<Series> series;
  int width_px = 1200;
  int height_px = 800;
};

// Throws std::invalid_argument when a series' x and y differ in length. Formats and failures as
// for WritePathFigure.
void WriteSeriesFigure(const std::filesystem::path& path, const SeriesFigureData& data);

// Consistency over time: ANEES per step with its χ² band (top panel), and position and heading
// RMSE per step (bottom panels).
struct ConsistencyFigureData {
  std::string title;
  std::vector<double> t_s;
  std::vector<double> anees;
  double band_lo = 0.0;
  double band_hi = 0.0;
  std::vector<double> position_rmse_m;
  std::vector<double> heading_rmse_rad;
  int width_px = 1200;
  int height_px = 1000;
};

// Each series is either empty (not drawn) or as long as `t_s`, else std::invalid_argument.
// Formats and failures as for WritePathFigure.
void WriteConsistencyFigure(const std::filesystem::path& path, const ConsistencyFigureData& data);

// One run on a contact sheet of occupancy-grid maps (WriteMapContactSheet).
struct MapSheetPanel {
  std::string title;          // e.g. "edmonton, seed 3: ATE 0.91 m"
  OccupancyImage map;         // as ReadOccupancyImage returns it (dark = occupied)
  Trajectory path;            // the estimated path, world frame, drawn over the map
  Trajectory secondary_path;  // drawn dimmer (e.g. raw odometry); empty: not drawn
  bool failed = false;        // a run that produced no map: the title and "no map" only
  // Drawn over the map in orange where it is known (e.g. P-SLAM's predicted cells; its own
  // extent, same resolution as `map`); empty: none.
  OccupancyImage overlay = {};
};

struct MapSheetData {
  std::string title;
  std::vector<MapSheetPanel> panels;
  int columns = 0;       // 0: about square, ceil(sqrt(panel count))
  int panel_px = 400;    // side of each panel in pixels
};

// A grid of panels, one per run, so that a broken map stands out: each map in grey (occupied
// dark, free light, unknown mid grey; pixels read as map_server does with its default
// thresholds), cropped to its known area and the path plus a margin, at equal scale on both
// axes, with the paths over it, a scale bar and the title above. A panel that is failed or has
// an empty map shows "no map". Large maps are merged into blocks of pixels first (a block is
// occupied if any of its pixels is, else free if any is), about one block per output pixel.
// The image is columns × panel_px wide and rows × panel_px high plus a title band when `title`
// is not empty. Throws std::invalid_argument when there is no panel, panel_px < 50, columns < 0
// or a map's pixels, resolution or origin are inconsistent; formats and failures as for
// WritePathFigure.
void WriteMapContactSheet(const std::filesystem::path& path, const MapSheetData& data);

// `points` points on the `sigma`-sigma contour of N(mean, cov), {mean + sigma L u : |u| = 1} with
// L Lᵀ = cov, evenly spaced in the angle of u; the first lies on the positive major semi-axis.
// The polyline is not closed (the caller repeats the first point). Negative eigenvalues of a
// slightly indefinite `cov` are treated as zero.
std::vector<Eigen::Vector2d> CovarianceEllipse(const Eigen::Vector2d& mean,
                                               const Eigen::Matrix2d& cov, double sigma,
                                               int points = 36);

}  // namespace slamkit
