#include "slamkit/io/run_errors_reader.hpp"

#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "slamkit/io/error.hpp"
#include "slamkit/io/numeric_csv.hpp"

namespace slamkit {
namespace {

const std::vector<std::string> kColumns = {"t_s", "error_x_m", "error_y_m", "error_theta_rad",
                                           "nees"};

// Field `i` of a row read from `where`: never NaN; finite, except the NEES (column 4), which may
// be +inf but not negative.
void CheckField(const std::string& where, std::size_t i, double value) {
  const auto fail = [&](const char* reason) {
    throw InputError(fmt::format("{}: field '{}': {} ('{}')", where, kColumns[i], reason, value));
  };
  if (std::isnan(value)) fail("not a number");
  if (i == 4 && value < 0.0) fail("a negative NEES");
  if (i < 4 && !std::isfinite(value)) fail("not a finite number");
}

}  // namespace

RunErrorsCsv ReadRunErrorsCsv(const std::filesystem::path& path) {
  const NumericCsv csv = ReadNumericCsv(path);
  if (csv.columns != kColumns) {
    throw InputError(fmt::format("{}:1: expected the header '{}'", path.string(),
                                 fmt::join(kColumns, ",")));
  }
  RunErrorsCsv out;
  for (std::size_t r = 0; r < csv.rows.size(); ++r) {
    const std::vector<double>& v = csv.rows[r];
    const std::string where = fmt::format("{}:{}", path.string(), csv.lines[r]);
    for (std::size_t i = 0; i < v.size(); ++i) CheckField(where, i, v[i]);
    out.t_s.push_back(v[0]);
    out.errors.emplace_back(v[1], v[2], v[3]);
    out.nees.push_back(v[4]);
  }
  return out;
}

}  // namespace slamkit
