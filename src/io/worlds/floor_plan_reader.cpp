// Floor plans written as walls and polygons: the text format users describe a building in.

#include "slamkit/io/floor_plan_reader.hpp"

#include <fmt/format.h>

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slamkit/io/error.hpp"
#include "../text/text_records.hpp"

namespace slamkit {
namespace {

constexpr std::string_view kPolyKeyword = "poly";
constexpr int kMinPolygonPoints = 3;

// Point k (1-based): the fields `x<k> y<k>`.
Eigen::Vector2d PointAt(const text::Fields& fields, int k) {
  const std::size_t i = 2 * static_cast<std::size_t>(k - 1);
  return {fields.Number(i, {"x", k}), fields.Number(i + 1, {"y", k})};
}

// A zero-length wall is almost always a typo, and would be invisible to the laser anyway.
void CheckDistinct(const text::Fields& fields, const std::vector<Eigen::Vector2d>& points,
                   int k, int previous, std::string_view hint) {
  if (points[k - 1] != points[previous - 1]) return;
  const std::string name = fmt::format("x{} y{}", k, k);
  fields.Fail({name}, fmt::format("the same point as x{} y{}: a zero-length wall{}", previous,
                                  previous, hint));
}

// `x1 y1 x2 y2`.
void ParseWall(const std::string& where, const text::Fields& fields,
               std::vector<WallSegment>* walls) {
  if (fields.size() != 4) {
    throw InputError(fmt::format("{}: expected 4 numbers `x1 y1 x2 y2` (or `poly x1 y1 x2 y2 "
                                 "x3 y3 ...`), got {} fields", where, fields.size()));
  }
  const std::vector<Eigen::Vector2d> points = {PointAt(fields, 1), PointAt(fields, 2)};
  CheckDistinct(fields, points, 2, 1, "");
  walls->emplace_back(points[0], points[1]);
}

// `poly x1 y1 ... xn yn` (the fields after the keyword): n walls around a closed polygon.
void ParsePolygon(const std::string& where, const text::Fields& fields,
                  std::vector<WallSegment>* walls) {
  if (fields.size() % 2 != 0) {
    throw InputError(fmt::format("{}: poly has {} numbers, expected `x y` pairs (an even count)",
                                 where, fields.size()));
  }
  const int n = static_cast<int>(fields.size() / 2);
  if (n < kMinPolygonPoints) {
    throw InputError(fmt::format("{}: poly has {} points, needs at least {}", where, n,
                                 kMinPolygonPoints));
  }
  std::vector<Eigen::Vector2d> points;
  points.reserve(n);
  for (int k = 1; k <= n; ++k) points.push_back(PointAt(fields, k));
  for (int k = 2; k <= n; ++k) CheckDistinct(fields, points, k, k - 1, "");
  CheckDistinct(fields, points, n, 1, " (the polygon closes itself: do not repeat x1 y1)");
  for (int k = 0; k < n; ++k) walls->emplace_back(points[k], points[(k + 1) % n]);
}

}  // namespace

Walls ReadFloorPlanFile(const std::filesystem::path& path) {
  text::LineReader reader(path);
  std::vector<WallSegment> walls;
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (reader.Next(&line)) {
    text::Tokenize(line.substr(0, line.find('#')), &tokens);  // `#` to the end: a comment
    if (tokens.empty()) continue;
    const std::string where = fmt::format("{}:{}", path.string(), reader.line_number());
    if (tokens[0] == kPolyKeyword) {
      ParsePolygon(where, text::Fields(where, kPolyKeyword, std::span(tokens).subspan(1)),
                   &walls);
    } else {
      ParseWall(where, text::Fields(where, "", tokens), &walls);
    }
  }
  if (walls.empty()) {
    throw InputError(fmt::format("{}: no walls: expected `x1 y1 x2 y2` or `poly x1 y1 x2 y2 x3 y3 "
                                 "...` lines, in metres", path.string()));
  }
  return walls;
}

}  // namespace slamkit
