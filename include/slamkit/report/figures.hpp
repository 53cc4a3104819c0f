#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "slamkit/core/trajectory.hpp"
#include "slamkit/maps/landmark_map.hpp"
#include "slamkit/sim/world.hpp"

namespace slamkit {

// What a map figure shows: the true and estimated paths, true landmarks and the estimated ones
// with their 2-sigma ellipses. Empty members are simply not drawn (a real data set has no truth).
struct PathFigureData {
  std::string title;
  Trajectory truth;
  Trajectory estimate;
  LandmarkWorld true_landmarks;
  LandmarkMap map;
  double ellipse_sigma = 2.0;
};

// Writes the figure as PNG or SVG, chosen by the extension, atomically (temp file + rename).
void WritePathFigure(const std::filesystem::path& path, const PathFigureData& data);

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
};

void WriteConsistencyFigure(const std::filesystem::path& path, const ConsistencyFigureData& data);

}  // namespace slamkit
