#include "slamkit/io/waypoints_reader.hpp"

#include <fmt/format.h>

#include <string>
#include <string_view>
#include <vector>

#include "slamkit/io/error.hpp"
#include "text_records.hpp"

namespace slamkit {

std::vector<Eigen::Vector2d> ReadWaypoints(const std::filesystem::path& path) {
  text::LineReader reader(path);
  std::vector<Eigen::Vector2d> waypoints;
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (reader.Next(&line)) {
    text::Tokenize(line, &tokens);
    if (tokens.empty() || tokens[0].starts_with('#')) continue;
    const std::string where = fmt::format("{}:{}", path.string(), reader.line_number());
    if (tokens.size() != 2) {
      throw InputError(fmt::format("{}: expected 2 fields `x y`, got {}", where, tokens.size()));
    }
    const text::Fields fields(where, "", tokens);
    waypoints.emplace_back(fields.Number(0, {"x"}), fields.Number(1, {"y"}));
  }
  if (waypoints.size() < 2) {
    throw InputError(fmt::format("{}: a route needs at least 2 waypoints, got {}", path.string(),
                                 waypoints.size()));
  }
  return waypoints;
}

}  // namespace slamkit
