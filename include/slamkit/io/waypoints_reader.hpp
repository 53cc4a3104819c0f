#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace slamkit {

// Reads a route's waypoints from a plain or gzip-compressed text file: one `x y` pair (metres,
// separated by spaces or tabs) per line; blank lines and lines starting with `#` are ignored. At
// least 2 waypoints. Throws InputError naming the file, the line and the field (x or y) for a
// missing, extra or non-numeric field or NaN/inf.
std::vector<Eigen::Vector2d> ReadWaypoints(const std::filesystem::path& path);

}  // namespace slamkit
