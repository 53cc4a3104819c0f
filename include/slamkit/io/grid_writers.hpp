#pragma once

#include <filesystem>

#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/maps/occupancy_image.hpp"

namespace slamkit {

struct GridImageParams {
  double occupied_threshold = 0.65;  // probability at or above which a cell is drawn occupied
  double free_threshold = 0.196;     // probability at or below which a cell is drawn free
  int margin_cells = 10;             // unknown border around the written area
};

// The grid as map_server's 8-bit image (free 254, occupied 0, unknown 205; top row = largest
// y), covering the written cells and a margin of unknown around them.
OccupancyImage RenderOccupancyImage(const OccupancyGrid& grid, const GridImageParams& params = {});

// ROS map_server convention: `map.pgm` (P5, 8 bit, top row = largest y; free 254, occupied 0,
// unknown 205) and `map.yaml` (image, resolution, origin [x, y, 0] of the lower-left pixel,
// negate 0, occupied_thresh, free_thresh). `pgm_path` names the image; the YAML goes beside it
// with the extension .yaml. Both files are written atomically.
void WriteOccupancyGridPgm(const std::filesystem::path& pgm_path, const OccupancyGrid& grid,
                           const GridImageParams& params = {});

// The same image as an 8-bit greyscale PNG (libpng), written atomically.
void WriteOccupancyGridPng(const std::filesystem::path& png_path, const OccupancyGrid& grid,
                           const GridImageParams& params = {});

}  // namespace slamkit
