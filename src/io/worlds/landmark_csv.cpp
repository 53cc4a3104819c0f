#include "slamkit/io/landmark_csv.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

constexpr const char* kLandmarkCsvFields[] = {"id", "x_m", "y_m"};

std::string_view Trim(std::string_view s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::vector<std::string_view> SplitFields(std::string_view line) {
  std::vector<std::string_view> fields;
  while (true) {
    const auto comma = line.find(',');
    fields.push_back(Trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return fields;
    line.remove_prefix(comma + 1);
  }
}

// Parses and checks one CSV line; `where` is the `file:line` prefix of any error.
class LineParser {
 public:
  explicit LineParser(std::string where) : where_(std::move(where)) {}

  [[noreturn]] void Fail(const std::string& reason) const {
    throw InputError(where_ + ": " + reason);
  }
  [[noreturn]] void FailField(int field, std::string_view reason, std::string_view text) const {
    Fail(fmt::format("field '{}': {} ('{}')", kLandmarkCsvFields[field], reason, text));
  }

  LandmarkId Id(std::string_view text) const {
    LandmarkId id = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), id);
    if (ec != std::errc() || end != text.data() + text.size()) FailField(0, "not an integer", text);
    if (id < 0) FailField(0, "negative id", text);
    return id;
  }

  double Coordinate(int field, std::string_view text) const {
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size()) {
      FailField(field, "not a number", text);
    }
    if (!std::isfinite(value)) FailField(field, "not a finite number", text);
    return value;
  }

 private:
  std::string where_;
};

bool IsHeader(const std::vector<std::string_view>& fields) {
  return fields.size() == 3 && fields[0] == "id" && fields[1] == "x_m" && fields[2] == "y_m";
}

}  // namespace

LandmarkWorld ReadLandmarkCsv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open file");
  LandmarkWorld world;
  std::unordered_map<LandmarkId, int> line_of_id;
  std::string line;
  bool first_record = true;
  for (int line_number = 1; std::getline(in, line); ++line_number) {
    const std::string_view text = Trim(line);
    if (text.empty() || text.front() == '#') continue;
    const std::vector<std::string_view> fields = SplitFields(text);
    if (std::exchange(first_record, false) && IsHeader(fields)) continue;
    const LineParser parser(fmt::format("{}:{}", path.string(), line_number));
    if (fields.size() > 3) parser.Fail(fmt::format("expected 3 fields, got {}", fields.size()));
    if (fields.size() < 3) {
      parser.Fail(fmt::format("field '{}': missing", kLandmarkCsvFields[fields.size()]));
    }
    for (int f = 0; f < 3; ++f) {
      if (fields[f].empty()) parser.Fail(fmt::format("field '{}': empty", kLandmarkCsvFields[f]));
    }
    Landmark landmark;
    landmark.id = parser.Id(fields[0]);
    landmark.position_m = {parser.Coordinate(1, fields[1]), parser.Coordinate(2, fields[2])};
    const auto [it, inserted] = line_of_id.emplace(landmark.id, line_number);
    if (!inserted) {
      parser.Fail(fmt::format("duplicate id {} (first on line {})", landmark.id, it->second));
    }
    world.landmarks.push_back(landmark);
  }
  if (in.bad()) throw InputError(path.string() + ": read error");
  if (world.landmarks.empty()) {
    throw InputError(path.string() + ": no landmarks (expected `id,x_m,y_m` lines)");
  }
  return world;
}

}  // namespace slamkit
