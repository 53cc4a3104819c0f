// map_server maps (YAML + binary PGM) read back into an OccupancyImage, for simulating a robot in
// a floor plan drawn as an image or built by an earlier SLAM run.

#include "slamkit/io/map_reader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <cctype>
#include <charconv>
#include <cstdint>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <ios>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slamkit/io/config_section.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

using config::Bound;
using config::Describe;
using config::Section;

// The image part of a map, as the PGM gives it.
struct PgmImage {
  std::vector<std::uint8_t> pixels;
  int width = 0;
  int height = 0;
};

// Netpbm header rules: fields separated by whitespace, `#` comments to the end of a line between
// fields, and exactly one whitespace byte between the last field and the pixels.
class PgmParser {
 public:
  PgmParser(std::string file, std::string bytes)
      : file_(std::move(file)), bytes_(std::move(bytes)) {}

  PgmImage Parse() {
    const std::string magic = bytes_.substr(0, 2);
    if (magic != "P5") {
      Fail(fmt::format("bad magic '{}' (expected 'P5', a binary greyscale PGM)", Printable(magic)));
    }
    pos_ = 2;
    PgmImage image;
    image.width = Field("width", kMaxSide);
    image.height = Field("height", kMaxSide);
    const int maxval = Field("maxval", 65535);
    if (maxval > 255) Fail(fmt::format("maxval {} (16-bit PGM) is not supported", maxval));
    if (pos_ >= bytes_.size() || !IsSpace(bytes_[pos_])) {
      Fail("truncated header: no whitespace after maxval");
    }
    ++pos_;
    const std::size_t expected = static_cast<std::size_t>(image.width) * image.height;
    if (expected > kMaxPixels) {
      Fail(fmt::format("{} × {} pixels is beyond the {} a map image may have", image.width,
                       image.height, kMaxPixels));
    }
    const std::size_t available = bytes_.size() - pos_;
    if (available < expected) {
      Fail(fmt::format("truncated pixel data: {} × {} needs {} bytes, the file has {}",
                       image.width, image.height, expected, available));
    }
    image.pixels.reserve(expected);
    for (std::size_t i = 0; i < expected; ++i) {
      const auto value = static_cast<std::uint8_t>(bytes_[pos_ + i]);
      if (value > maxval) Fail(fmt::format("pixel {} is {}, above maxval {}", i, value, maxval));
      // Rounded scaling to 0–255, so that maxval 255 leaves every value as it is.
      image.pixels.push_back(static_cast<std::uint8_t>((value * 255 + maxval / 2) / maxval));
    }
    return image;
  }

 private:
  // Larger sides are taken for a corrupt header rather than allocated.
  static constexpr int kMaxSide = 1 << 16;

 public:
  // 16384 × 16384: 820 m square at 5 cm, and what ReadPgm reads at most (with a header of up to
  // kMaxHeaderBytes), so that /dev/zero or a huge file fails before memory runs out.
  static constexpr std::size_t kMaxPixels = std::size_t{1} << 28;
  static constexpr std::size_t kMaxHeaderBytes = std::size_t{1} << 20;

 private:

  static bool IsSpace(char c) { return std::isspace(static_cast<unsigned char>(c)) != 0; }

  static std::string Printable(std::string_view text) {
    std::string out;
    for (const char c : text) {
      out += std::isprint(static_cast<unsigned char>(c)) ? std::string(1, c)
                                                         : fmt::format("\\x{:02x}", c & 0xff);
    }
    return out;
  }

  [[noreturn]] void Fail(const std::string& reason) const {
    throw InputError(fmt::format("{}: PGM {}", file_, reason));
  }

  void SkipSpaceAndComments() {
    while (pos_ < bytes_.size()) {
      if (IsSpace(bytes_[pos_])) {
        ++pos_;
      } else if (bytes_[pos_] == '#') {
        while (pos_ < bytes_.size() && bytes_[pos_] != '\n' && bytes_[pos_] != '\r') ++pos_;
      } else {
        return;
      }
    }
  }

  // The next header field as an integer in [1, max].
  int Field(const char* name, int max) {
    SkipSpaceAndComments();
    const std::size_t start = pos_;
    while (pos_ < bytes_.size() && !IsSpace(bytes_[pos_]) && bytes_[pos_] != '#') ++pos_;
    const std::string_view text(bytes_.data() + start, pos_ - start);
    if (text.empty()) Fail(fmt::format("header field '{}': missing (truncated header)", name));
    int value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || value < 1 || value > max) {
      Fail(fmt::format("header field '{}': expected an integer in [1, {}], got '{}'", name, max,
                       Printable(text.substr(0, 32))));
    }
    return value;
  }

  std::string file_;
  std::string bytes_;
  std::size_t pos_ = 0;
};

// `yaml` is the map file naming the image, for the messages.
PgmImage ReadPgm(const std::filesystem::path& path, const std::string& yaml) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec)) {
    throw InputError(fmt::format("{}: not a regular file (a directory, device or FIFO; the image "
                                 "of {})",
                                 path.string(), yaml));
  }
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > PgmParser::kMaxPixels + PgmParser::kMaxHeaderBytes) {
    throw InputError(fmt::format("{}: {} bytes, beyond the {} pixels a map image may have (the "
                                 "image of {})",
                                 path.string(), size, PgmParser::kMaxPixels, yaml));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw InputError(fmt::format("{}: cannot open file (the image of {})", path.string(), yaml));
  }
  std::string bytes;
  try {
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  } catch (const std::ios_base::failure&) {  // e.g. EISDIR, EIO
    throw InputError(fmt::format("{}: read error (the image of {})", path.string(), yaml));
  }
  if (in.bad()) throw InputError(path.string() + ": read error");
  return PgmParser(path.string(), std::move(bytes)).Parse();
}

void RequireKeys(const Section& s, std::initializer_list<const char*> keys) {
  for (const char* key : keys) {
    if (!s.Has(key)) s.Fail(key, "required (a map_server map names image, resolution, origin)");
  }
}

// `origin`: [x, y] or [x, y, yaw]; a rotated map has no OccupancyImage equivalent.
Eigen::Vector2d ReadOrigin(const Section& s) {
  const YAML::Node node = s.Get("origin");
  if (!node.IsSequence() || node.size() < 2 || node.size() > 3) {
    s.Fail("origin", "expected [x, y, yaw], got " + Describe(node));
  }
  const Eigen::Vector2d origin(s.Number("origin", node[0], Bound::kFinite),
                               s.Number("origin", node[1], Bound::kFinite));
  if (node.size() == 3 && s.Number("origin", node[2], Bound::kFinite) != 0.0) {
    s.Fail("origin", "yaw must be 0 (rotated maps are not supported)");
  }
  return origin;
}

// The optional keys, checked so that a typo or a map we would misread is reported.
bool ReadNegate(const Section& s) {
  int negate = 0;
  s.Read("negate", &negate, 0);
  if (negate > 1) s.Fail("negate", fmt::format("must be 0 or 1, got {}", negate));
  for (const char* key : {"occupied_thresh", "free_thresh"}) {
    double threshold = 0.0;
    s.Read(key, &threshold, Bound::kNonNegative);
    if (threshold > 1.0) s.Fail(key, fmt::format("must be in [0, 1], got {}", threshold));
  }
  config::ReadChoice(s, "mode", {"trinary", "scale"}, 0);
  return negate == 1;
}

}  // namespace

OccupancyImage ReadOccupancyImage(const std::filesystem::path& yaml_path) {
  const Section s(config::LoadYamlFile(yaml_path), yaml_path.string(), "",
                  {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh",
                   "mode"});
  RequireKeys(s, {"image", "resolution", "origin"});
  OccupancyImage image;
  std::string image_name;
  s.Read("image", &image_name);
  if (image_name.empty()) s.Fail("image", "must name the PGM file");
  if (image_name.find('\0') != std::string::npos) s.Fail("image", "contains a NUL byte");
  s.Read("resolution", &image.resolution_m, Bound::kPositive);
  image.origin_m = ReadOrigin(s);
  const bool negate = ReadNegate(s);
  // Relative image paths are relative to the YAML's folder (map_server's rule); `/` keeps an
  // absolute one as it is.
  const std::filesystem::path pgm_path = yaml_path.parent_path() / image_name;
  std::error_code ec;
  if (std::filesystem::is_directory(pgm_path, ec)) {
    s.Fail("image", fmt::format("'{}' is a directory, not a PGM file", pgm_path.string()));
  }
  PgmImage pgm = ReadPgm(pgm_path, yaml_path.string());
  image.width = pgm.width;
  image.height = pgm.height;
  image.pixels = std::move(pgm.pixels);
  if (negate) {
    for (std::uint8_t& p : image.pixels) p = static_cast<std::uint8_t>(255 - p);
  }
  return image;
}

}  // namespace slamkit
