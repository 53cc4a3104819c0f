#include "slamkit/io/numeric_csv.hpp"

#include <charconv>
#include <string_view>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"
#include "text_records.hpp"

namespace slamkit {
namespace {

std::vector<std::string_view> Split(std::string_view line) {
  std::vector<std::string_view> fields;
  while (true) {
    const auto comma = line.find(',');
    fields.push_back(line.substr(0, comma));
    if (comma == std::string_view::npos) return fields;
    line.remove_prefix(comma + 1);
  }
}

}  // namespace

int NumericCsv::Column(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return static_cast<int>(i);
  }
  return -1;
}

NumericCsv ReadNumericCsv(const std::filesystem::path& path) {
  text::LineReader reader(path);
  NumericCsv out;
  std::string_view line;
  if (!reader.Next(&line) || line.empty()) {
    throw InputError(path.string() + ":1: expected a header line of column names");
  }
  for (std::string_view name : Split(line)) out.columns.emplace_back(name);
  while (reader.Next(&line)) {
    if (line.empty()) continue;
    const std::vector<std::string_view> fields = Split(line);
    const std::string where = fmt::format("{}:{}", path.string(), reader.line_number());
    if (fields.size() != out.columns.size()) {
      throw InputError(fmt::format("{}: expected {} comma-separated fields (the header's), got {}",
                                   where, out.columns.size(), fields.size()));
    }
    std::vector<double> row(fields.size());
    for (std::size_t i = 0; i < fields.size(); ++i) {
      const std::string_view f = fields[i];
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), row[i]);
      if (f.empty() || ec != std::errc() || end != f.data() + f.size()) {
        throw InputError(fmt::format("{}: field '{}': not a number ('{}')", where,
                                     out.columns[i], text::Printable(f)));
      }
    }
    out.rows.push_back(std::move(row));
    out.lines.push_back(reader.line_number());
  }
  return out;
}

}  // namespace slamkit
