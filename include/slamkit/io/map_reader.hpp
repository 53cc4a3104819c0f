#pragma once

#include <filesystem>

#include "slamkit/maps/occupancy_image.hpp"

namespace slamkit {

// Reads a ROS map_server map: the YAML and the binary greyscale PGM it names (what
// WriteOccupancyGridPgm writes, see io/grid_writers.hpp). YAML keys: `image` (the PGM, relative
// to the YAML's folder unless absolute), `resolution` (m per pixel, > 0) and `origin` ([x, y] or
// [x, y, yaw] of the lower-left pixel's lower-left corner; yaw must be 0), all required;
// `negate` (0 or 1: 1 flips the pixels so that dark means occupied either way),
// `occupied_thresh`, `free_thresh` (in [0, 1]) and `mode` (trinary or scale) are checked but do
// not change the image. Other keys are errors. The PGM must be P5 with maxval ≤ 255; maxval < 255
// is scaled to 0–255 (as map_server's image loader does). Throws InputError naming the file and
// the key (with its line) or the PGM field: bad magic, bad header numbers, truncated pixel data,
// a missing key, ...
OccupancyImage ReadOccupancyImage(const std::filesystem::path& yaml_path);

}  // namespace slamkit
