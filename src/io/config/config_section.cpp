#include "slamkit/io/config_section.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/depthguard.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <utility>

#include "slamkit/core/angle.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit::config {
namespace {

// A YAML number; yaml-cpp's conversion also accepts the YAML spellings of infinity and NaN
// (`.inf`, `.nan`), which the callers reject as non-finite with their own message.
std::optional<double> ParseNumber(const YAML::Node& node) {
  double value = 0.0;
  if (!YAML::convert<double>::decode(node, value)) return std::nullopt;
  return value;
}

template <typename T>
std::optional<T> ParseInteger(const YAML::Node& node) {
  if (!node.IsScalar()) return std::nullopt;
  const std::string& text = node.Scalar();
  T value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// ":line" for a known mark, "" for yaml-cpp's null mark.
std::string LineOf(const YAML::Mark& mark) {
  return mark.is_null() ? std::string() : fmt::format(":{}", mark.line + 1);
}

}  // namespace

YAML::Node LoadYamlFile(const std::filesystem::path& path) {
  // yaml-cpp reads the whole stream: a device or a FIFO would never end, a huge file not fit.
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw InputError(path.string() + ": not a regular file (a directory, device or FIFO)");
  }
  constexpr std::uintmax_t kMaxYamlBytes = std::uintmax_t{64} << 20;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > kMaxYamlBytes) {
    throw InputError(fmt::format("{}: {} bytes, beyond the 64 MiB a config file may have",
                                 path.string(), size));
  }
  try {
    return YAML::LoadFile(path.string());
  } catch (const YAML::BadFile&) {
    throw InputError(path.string() + ": cannot open file");
  } catch (const YAML::DeepRecursion& e) {
    // Thrown for nesting of about 1000 levels, with msg "bad file", which misleads.
    throw InputError(
        fmt::format("{}{}: YAML nesting deeper than yaml-cpp supports (recursion depth {})",
                    path.string(), LineOf(e.mark), e.depth()));
  } catch (const YAML::ParserException& e) {
    throw InputError(
        fmt::format("{}{}: YAML syntax error: {}", path.string(), LineOf(e.mark), e.msg));
  } catch (const YAML::Exception& e) {
    throw InputError(fmt::format("{}{}: YAML error: {}", path.string(), LineOf(e.mark), e.msg));
  }
}

std::string Describe(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a sequence";
  if (node.IsMap()) return "a map";
  return "nothing";
}

Section::Section(const YAML::Node& node, std::string file, std::string path,
                 std::vector<std::string> known)
    : node_(node), file_(std::move(file)), path_(std::move(path)) {
  if (!node_.IsNull() && !node_.IsMap()) {
    FailAt(node_,
           fmt::format("{}: expected a map, got {}",
                       path_.empty() ? "the file" : "key '" + path_ + "'", Describe(node_)));
  }
  if (node_.IsMap()) CheckKeys(known);
}

Section Section::Child(const std::string& key, std::vector<std::string> known) const {
  const YAML::Node child = Has(key) ? Get(key) : YAML::Node();
  return Section(child, file_, Path(key), std::move(known));
}

void Section::Fail(const std::string& key, const std::string& reason) const {
  const auto it = line_of_key_.find(key);
  const std::string line = it == line_of_key_.end() ? "" : fmt::format("{}:", it->second);
  throw InputError(fmt::format("{}:{} key '{}': {}", file_, line, Path(key), reason));
}

void Section::FailAt(const YAML::Node& at, const std::string& message) const {
  throw InputError(fmt::format("{}:{}: {}", file_, at.Mark().line + 1, message));
}

double Section::Number(const std::string& key, const YAML::Node& value, Bound bound) const {
  const std::optional<double> v = ParseNumber(value);
  if (!v) Fail(key, "expected a number, got " + Describe(value));
  if (!std::isfinite(*v)) Fail(key, "must be a finite number, got " + Describe(value));
  if (bound == Bound::kPositive && *v <= 0.0) Fail(key, fmt::format("must be > 0, got {}", *v));
  if (bound == Bound::kNonNegative && *v < 0.0) {
    Fail(key, fmt::format("must be >= 0, got {}", *v));
  }
  return *v;
}

void Section::Read(const std::string& key, double* out, Bound bound) const {
  if (Has(key)) *out = Number(key, Get(key), bound);
}

void Section::ReadDegrees(const std::string& key, double* out_rad, Bound bound) const {
  if (!Has(key)) return;
  const double rad = DegToRad(Number(key, Get(key), bound));
  // deg·π overflows for |deg| above about 5.7e307: the radians must be finite as well.
  if (!std::isfinite(rad)) Fail(key, "too large to convert to radians, got " + Describe(Get(key)));
  *out_rad = rad;
}

void Section::Read(const std::string& key, int* out, int min) const {
  if (!Has(key)) return;
  const std::optional<int> v = ParseInteger<int>(Get(key));
  if (!v) Fail(key, "expected an integer, got " + Describe(Get(key)));
  if (*v < min) Fail(key, fmt::format("must be >= {}, got {}", min, *v));
  *out = *v;
}

void Section::Read(const std::string& key, std::uint64_t* out) const {
  if (!Has(key)) return;
  const std::optional<std::uint64_t> v = ParseInteger<std::uint64_t>(Get(key));
  if (!v) Fail(key, "expected a non-negative integer, got " + Describe(Get(key)));
  *out = *v;
}

void Section::Read(const std::string& key, bool* out) const {
  if (Has(key) && !YAML::convert<bool>::decode(Get(key), *out)) {
    Fail(key, "expected true or false, got " + Describe(Get(key)));
  }
}

void Section::Read(const std::string& key, std::string* out) const {
  if (!Has(key)) return;
  if (!Get(key).IsScalar()) Fail(key, "expected a string, got " + Describe(Get(key)));
  *out = Get(key).Scalar();
}

Eigen::Vector2d Section::Point(const std::string& key, const YAML::Node& value) const {
  if (!value.IsSequence() || value.size() != 2) {
    Fail(key, "expected a point [x, y], got " + Describe(value));
  }
  return {Number(key, value[0], Bound::kFinite), Number(key, value[1], Bound::kFinite)};
}

void Section::Read(const std::string& key, Eigen::Vector2d* out) const {
  if (Has(key)) *out = Point(key, Get(key));
}

void Section::CheckKeys(const std::vector<std::string>& known) {
  for (const auto& entry : node_) {
    const std::string key = entry.first.Scalar();
    if (std::find(known.begin(), known.end(), key) == known.end()) {
      FailAt(entry.first, fmt::format("unknown key '{}' in section '{}' (known: {})", key,
                                      path_.empty() ? "root" : path_, fmt::join(known, ", ")));
    }
    const auto [it, inserted] = line_of_key_.emplace(key, entry.first.Mark().line + 1);
    if (!inserted) {
      FailAt(entry.first,
             fmt::format("duplicate key '{}' (first on line {})", Path(key), it->second));
    }
  }
}

int ReadChoice(const Section& s, const std::string& key, const std::vector<std::string>& names,
               int fallback) {
  std::string value;
  s.Read(key, &value);
  if (!s.Has(key)) return fallback;
  const auto it = std::find(names.begin(), names.end(), value);
  if (it == names.end()) {
    s.Fail(key, fmt::format("expected one of {}, got '{}'", fmt::join(names, ", "), value));
  }
  return static_cast<int>(it - names.begin());
}

}  // namespace slamkit::config
