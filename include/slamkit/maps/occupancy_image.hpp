#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace slamkit {

// An 8-bit map image, such as a map_server PGM (see io/grid_writers.hpp).
struct OccupancyImage {
  std::vector<std::uint8_t> pixels;  // row-major, top row (largest y) first
  int width = 0;
  int height = 0;
  double resolution_m = 0.05;        // side of a pixel
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // lower-left corner of the lower-left pixel
};

}  // namespace slamkit
