#include "slamkit/io/run_errors_reader.hpp"

#include <charconv>
#include <cmath>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"
#include "text_records.hpp"

namespace slamkit {
namespace {

constexpr const char* kHeader = "t_s,error_x_m,error_y_m,error_theta_rad,nees";
constexpr const char* kFields[] = {"t_s", "error_x_m", "error_y_m", "error_theta_rad", "nees"};

// Field `i` of `where`'s line; finite unless `allow_inf` (then +inf too; never NaN or < 0).
double ParseField(const std::string& where, int i, std::string_view text, bool allow_inf) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  const auto fail = [&](const char* reason) {
    throw InputError(fmt::format("{}: field '{}': {} ('{}')", where, kFields[i], reason,
                                 text::Printable(text)));
  };
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) fail("not a number");
  if (std::isnan(value)) fail("not a number");
  if (allow_inf && value < 0.0) fail("a negative NEES");
  if (!allow_inf && !std::isfinite(value)) fail("not a finite number");
  return value;
}

}  // namespace

RunErrorsCsv ReadRunErrorsCsv(const std::filesystem::path& path) {
  text::LineReader reader(path);
  RunErrorsCsv out;
  std::string_view line;
  if (!reader.Next(&line) || line != kHeader) {
    throw InputError(fmt::format("{}:1: expected the header '{}'", path.string(), kHeader));
  }
  while (reader.Next(&line)) {
    const std::string where = fmt::format("{}:{}", path.string(), reader.line_number());
    double v[5];
    for (int i = 0; i < 5; ++i) {
      const auto comma = line.find(',');
      if ((i < 4) != (comma != std::string_view::npos)) {
        throw InputError(fmt::format("{}: expected 5 comma-separated fields", where));
      }
      v[i] = ParseField(where, i, line.substr(0, comma), i == 4);
      line.remove_prefix(i < 4 ? comma + 1 : line.size());
    }
    out.t_s.push_back(v[0]);
    out.errors.emplace_back(v[1], v[2], v[3]);
    out.nees.push_back(v[4]);
  }
  return out;
}

}  // namespace slamkit
