// Occupancy grid images in the ROS map_server format (PGM + YAML) and as PNG.

#include "slamkit/io/grid_writers.hpp"

#include <fmt/format.h>
#include <png.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "slamkit/io/atomic_file.hpp"

namespace slamkit {
namespace {

constexpr std::uint8_t kOccupiedPixel = 0;
constexpr std::uint8_t kFreePixel = 254;
constexpr std::uint8_t kUnknownPixel = 205;

// The pixel of each stored cell value (OccupancyGrid::LogOddsSteps): a cell never written, or
// back to exactly 0 log-odds, is unknown; the others are classified by their probability.
std::array<std::uint8_t, 256> PixelTable(const GridImageParams& params) {
  std::array<std::uint8_t, 256> table{};
  for (int v = -128; v < 128; ++v) {
    const auto steps = static_cast<OccupancyGrid::CellValue>(v);
    const double p = OccupancyGrid::StepsProbability(steps);
    table[static_cast<std::uint8_t>(steps)] = steps == 0                       ? kUnknownPixel
                                              : p >= params.occupied_threshold ? kOccupiedPixel
                                              : p <= params.free_threshold     ? kFreePixel
                                                                               : kUnknownPixel;
  }
  return table;
}

// Cells lo_x..hi_x of row y as pixels, one tile lookup per tile the row crosses.
void RenderRow(const OccupancyGrid& grid, const std::array<std::uint8_t, 256>& table, int y,
               int lo_x, int hi_x, std::uint8_t* out) {
  constexpr int kSize = OccupancyGrid::kTileSize, kMask = kSize - 1;
  for (int x = lo_x; x <= hi_x;) {
    const int tile_end = std::min(hi_x + 1, ((x >> OccupancyGrid::kTileBits) + 1) * kSize);
    const OccupancyGrid::CellValue* tile = grid.TileSteps({x, y});
    if (tile == nullptr) {
      out = std::fill_n(out, tile_end - x, kUnknownPixel);
      x = tile_end;
      continue;
    }
    const OccupancyGrid::CellValue* row = tile + (y & kMask) * kSize;
    for (; x < tile_end; ++x) *out++ = table[static_cast<std::uint8_t>(row[x & kMask])];
  }
}

// A YAML scalar for a file name: plain when that is safe, else double-quoted and escaped.
std::string YamlScalar(const std::string& text) {
  const bool plain = !text.empty() && text.find_first_not_of(
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-+/") == std::string::npos;
  if (plain) return text;
  std::string quoted = "\"";
  for (const char ch : text) {
    if (ch == '"' || ch == '\\') quoted += '\\';
    quoted += ch;
  }
  return quoted + '"';
}

// The map_server YAML; numbers are written in their shortest exact form, so they read back equal.
std::string MapYaml(const std::string& image_name, const OccupancyImage& image,
                    const OccupancyGrid& grid, const GridImageParams& params) {
  return fmt::format(
      "image: {}\nresolution: {}\norigin: [{}, {}, 0.0]\nnegate: 0\noccupied_thresh: {}\n"
      "free_thresh: {}\n",
      YamlScalar(image_name), grid.resolution(), image.origin_m.x(), image.origin_m.y(),
      params.occupied_threshold, params.free_threshold);
}

// PNG bytes of `image` through libpng's simplified API (no setjmp/longjmp in our frames).
std::string EncodePng(const OccupancyImage& image) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_GRAY;
  png_alloc_size_t size = 0;
  const png_int_32 stride = image.width;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.pixels.data(), stride, nullptr)) {
    throw std::runtime_error(std::string("PNG encoding failed: ") + png.message);
  }
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.pixels.data(), stride,
                                 nullptr)) {
    throw std::runtime_error(std::string("PNG encoding failed: ") + png.message);
  }
  bytes.resize(size);
  return bytes;
}

}  // namespace

// The image covers [min_cell - margin, max_cell + margin]. A grid with nothing written is drawn as
// if cell (0, 0) had been: a (1 + 2·margin)-pixel square of unknown around the world origin, so
// that a map of a run that produced no scan is still a valid, loadable map.
OccupancyImage RenderOccupancyImage(const OccupancyGrid& grid, const GridImageParams& params) {
  if (params.margin_cells < 0) throw std::invalid_argument("grid image: negative margin_cells");
  CellIndex lo = grid.min_cell();
  CellIndex hi = grid.max_cell();
  if (lo.x > hi.x || lo.y > hi.y) lo = hi = CellIndex{0, 0};
  const int m = params.margin_cells;
  lo = {lo.x - m, lo.y - m};
  hi = {hi.x + m, hi.y + m};
  OccupancyImage image;
  image.width = hi.x - lo.x + 1;
  image.height = hi.y - lo.y + 1;
  image.resolution_m = grid.resolution();
  image.origin_m = {lo.x * grid.resolution(), lo.y * grid.resolution()};
  image.pixels.resize(static_cast<std::size_t>(image.width) * image.height);
  const std::array<std::uint8_t, 256> table = PixelTable(params);
  for (int y = hi.y; y >= lo.y; --y) {
    RenderRow(grid, table, y, lo.x, hi.x,
              &image.pixels[static_cast<std::size_t>(hi.y - y) * image.width]);
  }
  return image;
}

void WriteOccupancyGridPgm(const std::filesystem::path& pgm_path, const OccupancyGrid& grid,
                           const GridImageParams& params) {
  const OccupancyImage image = RenderOccupancyImage(grid, params);
  WriteFileAtomically(pgm_path, [&image](std::ostream& out) {
    out << "P5\n" << image.width << ' ' << image.height << "\n255\n";
    out.write(reinterpret_cast<const char*>(image.pixels.data()),
              static_cast<std::streamsize>(image.pixels.size()));
  });
  // The YAML goes second so that it never names an image that is not there.
  std::filesystem::path yaml_path = pgm_path;
  yaml_path.replace_extension(".yaml");
  WriteFileAtomically(yaml_path, MapYaml(pgm_path.filename().string(), image, grid, params));
}

void WriteOccupancyGridPng(const std::filesystem::path& png_path, const OccupancyGrid& grid,
                           const GridImageParams& params) {
  const OccupancyImage image = RenderOccupancyImage(grid, params);
  WriteFileAtomically(png_path, EncodePng(image));
}

}  // namespace slamkit
