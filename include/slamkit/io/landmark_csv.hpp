#pragma once

#include <filesystem>

#include "slamkit/core/landmark_world.hpp"

namespace slamkit {

// Reads a landmark world from CSV: an optional header line `id,x_m,y_m`, then one landmark per
// line as `id,x,y` (metres). Throws InputError naming the file, line and field for a missing or
// non-numeric field, NaN or infinity, or a repeated id.
LandmarkWorld ReadLandmarkCsv(const std::filesystem::path& path);

}  // namespace slamkit
