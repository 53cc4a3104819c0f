#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/runners/features/explore_run.hpp"

namespace slamkit::app {

// What `explore` and `features` write of a line-and-corner map.

// lines.csv: one line landmark per row, its world line, covariance and seen extent.
void WriteLinesCsv(const std::filesystem::path& path, const std::vector<MappedLine>& lines);

// map.png of a run on a log: the mapped lines and corners over the scans' returns as the
// estimate placed them, with the estimated path. (Not the odometry: a log's raw odometry can
// drift tens of metres off, and the figure would be scaled to it, the map a small patch.)
void WriteFeatureMapFigure(const std::filesystem::path& path, const std::string& title,
                           const std::vector<MappedLine>& lines,
                           const std::vector<Eigen::Vector2d>& corners,
                           const std::vector<Eigen::Vector2d>& points,
                           const Trajectory& estimate);

}  // namespace slamkit::app
