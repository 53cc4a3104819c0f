#include "slamkit/io/grid_writers.hpp"

#include <gtest/gtest.h>
#include <png.h>
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;

constexpr int kMargin = 2;

// Occupied (3, 5), free (1, 2), written but undecided (2, 2): cells [1, 3] × [2, 5], so with a
// margin of 2 the image covers x in [-1, 5] and y in [0, 7], 7 × 8 pixels.
OccupancyGrid SmallGrid() {
  OccupancyGrid grid({.resolution_m = 0.05});
  grid.Update({3, 5}, 4.0f);
  grid.Update({1, 2}, -4.0f);
  grid.Update({2, 2}, 0.1f);
  return grid;
}

GridImageParams SmallParams() { return {.occupied_threshold = 0.7, .free_threshold = 0.25,
                                        .margin_cells = kMargin}; }

// The pixel of cell (x, y) in the SmallGrid image: rows from y = 7 down, columns from x = -1.
std::size_t PixelIndex(int x, int y) { return static_cast<std::size_t>((7 - y) * 7 + (x + 1)); }

class GridWriters : public testing::TempDirTest {
 protected:
  int FilesInDir() const {
    int n = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++n;
    return n;
  }
};

TEST_F(GridWriters, PgmHasTheHeaderAndThePixelsTopRowFirst) {
  WriteOccupancyGridPgm(dir_ / "map.pgm", SmallGrid(), SmallParams());
  const std::string pgm = testing::ReadText(dir_ / "map.pgm");
  const std::string header = "P5\n7 8\n255\n";
  ASSERT_EQ(pgm.size(), header.size() + 7 * 8);
  EXPECT_EQ(pgm.substr(0, header.size()), header);
  const auto pixel = [&](int x, int y) {
    return static_cast<int>(static_cast<std::uint8_t>(pgm[header.size() + PixelIndex(x, y)]));
  };
  EXPECT_EQ(pixel(3, 5), 0);     // occupied, in row 2
  EXPECT_EQ(pixel(1, 2), 254);   // free, in row 5
  EXPECT_EQ(pixel(2, 2), 205);   // written, between the thresholds
  EXPECT_EQ(pixel(-1, 7), 205);  // never written (top-left corner)
  EXPECT_EQ(pixel(5, 0), 205);   // never written (bottom-right corner)
  int unknown = 0;
  for (std::size_t i = header.size(); i < pgm.size(); ++i) unknown += pgm[i] == char(205);
  EXPECT_EQ(unknown, 7 * 8 - 2);
}

// Across tiles, on both sides of the origin, with cells written back to exactly 0 log-odds: every
// pixel is what the cell's own probability says (the image is built a tile row at a time).
TEST_F(GridWriters, EveryPixelClassifiesItsCellAcrossTiles) {
  OccupancyGrid grid({.resolution_m = 0.05});
  std::mt19937 random(5);
  std::uniform_int_distribution<int> coordinate(-150, 149), steps(-127, 127);
  for (int i = 0; i < 20000; ++i) {
    const CellIndex c{coordinate(random), coordinate(random)};
    grid.Update(c, steps(random) / 32.0f);
    if (i % 7 == 0) grid.Update(c, -grid.LogOdds(c));  // known once, unknown again
  }
  const GridImageParams params{.occupied_threshold = 0.6, .free_threshold = 0.3, .margin_cells = 3};
  const OccupancyImage image = RenderOccupancyImage(grid, params);
  const CellIndex lo{grid.min_cell().x - 3, grid.min_cell().y - 3};
  ASSERT_EQ(image.width, grid.max_cell().x - lo.x + 4);
  ASSERT_EQ(image.height, grid.max_cell().y - lo.y + 4);
  for (int row = 0; row < image.height; ++row) {
    for (int col = 0; col < image.width; ++col) {
      const CellIndex c{lo.x + col, lo.y + image.height - 1 - row};
      const double p = grid.Probability(c);
      const int want = !grid.IsKnown(c)                  ? 205
                       : p >= params.occupied_threshold ? 0
                       : p <= params.free_threshold     ? 254
                                                        : 205;
      ASSERT_EQ(image.pixels[static_cast<std::size_t>(row) * image.width + col], want)
          << "cell (" << c.x << ", " << c.y << ")";
    }
  }
}

TEST_F(GridWriters, YamlHasTheMapServerFields) {
  WriteOccupancyGridPgm(dir_ / "map.pgm", SmallGrid(), SmallParams());
  const YAML::Node yaml = YAML::LoadFile((dir_ / "map.yaml").string());
  EXPECT_EQ(yaml["image"].as<std::string>(), "map.pgm");
  EXPECT_EQ(yaml["resolution"].as<double>(), 0.05);
  ASSERT_EQ(yaml["origin"].size(), 3u);
  // The lower-left corner of the lower-left pixel, cell (1 - 2, 2 - 2).
  EXPECT_EQ(yaml["origin"][0].as<double>(), -1 * 0.05);
  EXPECT_EQ(yaml["origin"][1].as<double>(), 0.0);
  EXPECT_EQ(yaml["origin"][2].as<double>(), 0.0);
  EXPECT_EQ(yaml["negate"].as<int>(), 0);
  EXPECT_EQ(yaml["occupied_thresh"].as<double>(), 0.7);
  EXPECT_EQ(yaml["free_thresh"].as<double>(), 0.25);
  EXPECT_EQ(FilesInDir(), 2);
}

TEST_F(GridWriters, OriginIsExactForNegativeCells) {
  OccupancyGrid grid({.resolution_m = 0.1});
  grid.Update({-37, -101}, 1.0f);
  WriteOccupancyGridPgm(dir_ / "neg.pgm", grid, {.margin_cells = 3});
  const YAML::Node yaml = YAML::LoadFile((dir_ / "neg.yaml").string());
  EXPECT_EQ(yaml["image"].as<std::string>(), "neg.pgm");
  EXPECT_EQ(yaml["origin"][0].as<double>(), -40 * 0.1);
  EXPECT_EQ(yaml["origin"][1].as<double>(), -104 * 0.1);
  EXPECT_EQ(yaml["occupied_thresh"].as<double>(), 0.65);
  EXPECT_EQ(yaml["free_thresh"].as<double>(), 0.196);
}

// Nothing written: a (1 + 2·margin)-pixel square of unknown around the world origin.
TEST_F(GridWriters, EmptyGridIsAnUnknownSquare) {
  WriteOccupancyGridPgm(dir_ / "map.pgm", OccupancyGrid(), {.margin_cells = 1});
  EXPECT_EQ(testing::ReadText(dir_ / "map.pgm"), "P5\n3 3\n255\n" + std::string(9, char(205)));
  const YAML::Node yaml = YAML::LoadFile((dir_ / "map.yaml").string());
  EXPECT_EQ(yaml["origin"][0].as<double>(), -0.05);
  EXPECT_EQ(yaml["origin"][1].as<double>(), -0.05);
}

std::vector<std::uint8_t> DecodeGrayPng(const std::string& bytes, png_uint_32* width,
                                        png_uint_32* height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) {
    throw std::runtime_error(image.message);
  }
  image.format = PNG_FORMAT_GRAY;
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) {
    throw std::runtime_error(image.message);
  }
  *width = image.width;
  *height = image.height;
  return pixels;
}

std::uint32_t BigEndian32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<std::uint8_t>(bytes[at + i]);
  return v;
}

TEST_F(GridWriters, PngIsAnEightBitGrayImageOfTheSamePixels) {
  WriteOccupancyGridPng(dir_ / "map.png", SmallGrid(), SmallParams());
  WriteOccupancyGridPgm(dir_ / "map.pgm", SmallGrid(), SmallParams());
  const std::string png = testing::ReadText(dir_ / "map.png");
  ASSERT_GE(png.size(), 33u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(BigEndian32(png, 16), 7u);
  EXPECT_EQ(BigEndian32(png, 20), 8u);
  EXPECT_EQ(static_cast<int>(png[24]), 8);  // bit depth
  EXPECT_EQ(static_cast<int>(png[25]), 0);  // colour type: greyscale

  png_uint_32 width = 0;
  png_uint_32 height = 0;
  const std::vector<std::uint8_t> pixels = DecodeGrayPng(png, &width, &height);
  ASSERT_EQ(width, 7u);
  ASSERT_EQ(height, 8u);
  EXPECT_EQ(pixels[PixelIndex(3, 5)], 0);
  EXPECT_EQ(pixels[PixelIndex(1, 2)], 254);
  EXPECT_EQ(pixels[PixelIndex(2, 2)], 205);
  const std::string pgm = testing::ReadText(dir_ / "map.pgm");
  EXPECT_EQ(std::string(pixels.begin(), pixels.end()), pgm.substr(pgm.size() - 7 * 8));
  EXPECT_EQ(FilesInDir(), 3);  // map.png, map.pgm, map.yaml: no temporaries left
}

TEST_F(GridWriters, UnwritableDirectoryThrowsAndLeavesNoFile) {
  EXPECT_THROW(WriteOccupancyGridPgm(dir_ / "missing" / "map.pgm", SmallGrid()),
               std::runtime_error);
  EXPECT_THROW(WriteOccupancyGridPng(dir_ / "missing" / "map.png", SmallGrid()),
               std::runtime_error);
  std::ofstream(dir_ / "plain_file") << "x";  // a file where a directory should be
  EXPECT_THROW(WriteOccupancyGridPgm(dir_ / "plain_file" / "map.pgm", SmallGrid()),
               std::runtime_error);
  EXPECT_THROW(WriteOccupancyGridPng(dir_ / "plain_file" / "map.png", SmallGrid()),
               std::runtime_error);
  EXPECT_EQ(FilesInDir(), 1);
}

TEST_F(GridWriters, ReadOnlyDirectoryThrowsAndLeavesNoFile) {
  const fs::path ro = dir_ / "ro";
  fs::create_directory(ro);
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
  if (std::ofstream(ro / "probe")) {
    fs::remove(ro / "probe");
    fs::permissions(ro, fs::perms::owner_all);
    GTEST_SKIP() << "permissions are not enforced for this user (root?)";
  }
  EXPECT_THROW(WriteOccupancyGridPgm(ro / "map.pgm", SmallGrid()), std::runtime_error);
  EXPECT_THROW(WriteOccupancyGridPng(ro / "map.png", SmallGrid()), std::runtime_error);
  EXPECT_TRUE(fs::is_empty(ro));
  fs::permissions(ro, fs::perms::owner_all);
}

TEST_F(GridWriters, RewritingReplacesTheFiles) {
  WriteOccupancyGridPgm(dir_ / "map.pgm", OccupancyGrid(), {.margin_cells = 0});
  WriteOccupancyGridPgm(dir_ / "map.pgm", SmallGrid(), SmallParams());
  EXPECT_EQ(testing::ReadText(dir_ / "map.pgm").substr(0, 11), "P5\n7 8\n255\n");
  EXPECT_EQ(FilesInDir(), 2);
}

}  // namespace
}  // namespace slamkit
