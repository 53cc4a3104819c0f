#include "slamkit/io/waypoints_reader.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>

#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

// The whitespace-separated fields of one line.
std::vector<std::string_view> SplitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  constexpr std::string_view kSpace = " \t\r";
  std::size_t pos = line.find_first_not_of(kSpace);
  while (pos != std::string_view::npos) {
    const std::size_t end = line.find_first_of(kSpace, pos);
    fields.push_back(line.substr(pos, end == std::string_view::npos ? end : end - pos));
    pos = line.find_first_not_of(kSpace, end);
  }
  return fields;
}

double Coordinate(const std::string& where, const char* name, std::string_view text) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    throw InputError(fmt::format("{}: field '{}': not a number ('{}')", where, name, text));
  }
  if (!std::isfinite(value)) {
    throw InputError(fmt::format("{}: field '{}': not a finite number ('{}')", where, name, text));
  }
  return value;
}

}  // namespace

std::vector<Eigen::Vector2d> ReadWaypoints(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open file");
  std::vector<Eigen::Vector2d> waypoints;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::vector<std::string_view> fields = SplitFields(line);
    if (fields.empty() || fields[0].starts_with('#')) continue;
    const std::string where = fmt::format("{}:{}", path.string(), number);
    if (fields.size() != 2) {
      throw InputError(fmt::format("{}: expected 2 fields `x y`, got {}", where, fields.size()));
    }
    waypoints.emplace_back(Coordinate(where, "x", fields[0]), Coordinate(where, "y", fields[1]));
  }
  if (in.bad()) throw InputError(path.string() + ": read error");
  if (waypoints.size() < 2) {
    throw InputError(fmt::format("{}: a route needs at least 2 waypoints, got {}", path.string(),
                                 waypoints.size()));
  }
  return waypoints;
}

}  // namespace slamkit
