#include "slamkit/io/waypoints_reader.hpp"

#include <fmt/format.h>

#include <vector>

#include "slamkit/io/error.hpp"
#include "../text/text_records.hpp"

namespace slamkit {

std::vector<Eigen::Vector2d> ReadWaypoints(const std::filesystem::path& path) {
  std::vector<Eigen::Vector2d> waypoints;
  text::ForEachRecord(path, [&](const text::Fields& fields) {
    if (fields.size() != 2) {
      throw InputError(fmt::format("{}: expected 2 fields `x y`, got {}", fields.where(),
                                   fields.size()));
    }
    waypoints.emplace_back(fields.Number(0, {"x"}), fields.Number(1, {"y"}));
  });
  if (waypoints.size() < 2) {
    throw InputError(fmt::format("{}: a route needs at least 2 waypoints, got {}", path.string(),
                                 waypoints.size()));
  }
  return waypoints;
}

}  // namespace slamkit
