#include "slamkit/io/map_reader.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"
#include "slamkit/io/grid_writers.hpp"

namespace slamkit {
namespace {

using testing::Contains;
using testing::InputErrorOf;

// The pixel of `image` that covers world point `p` (top row first, as map_server stores it).
std::uint8_t PixelAt(const OccupancyImage& image, const Eigen::Vector2d& p) {
  const Eigen::Vector2d at = (p - image.origin_m) / image.resolution_m;
  const int column = static_cast<int>(std::floor(at.x()));
  const int row = static_cast<int>(std::floor(at.y()));
  EXPECT_TRUE(column >= 0 && column < image.width && row >= 0 && row < image.height);
  return image.pixels[static_cast<std::size_t>(image.height - 1 - row) * image.width + column];
}

class MapReader : public testing::TempDirTest {
 protected:
  // A 3 × 2 map beside `name`.yaml; `pgm` is the whole image file.
  std::filesystem::path WriteMap(const std::string& pgm, const std::string& yaml_extra = "",
                                 const std::string& resolution = "resolution: 0.1\n") {
    WriteFile("map.pgm", pgm);
    return WriteFile("map.yaml", "image: map.pgm\n" + resolution + "origin: [-1.5, 2.0, 0.0]\n" +
                                     yaml_extra);
  }
  static std::string Pgm(const std::string& header = "P5\n3 2\n255\n") {
    return header + std::string("\x00\xfe\xcd\x10\x20\x30", 6);
  }
};

// What WriteOccupancyGridPgm writes reads back pixel for pixel, and each cell's pixel is where
// the origin and resolution put it.
TEST_F(MapReader, RoundTripsTheGridWriter) {
  OccupancyGrid grid({.resolution_m = 0.1});
  grid.Update({-7, 12}, 4.0f);   // occupied → 0
  grid.Update({5, -3}, -4.0f);   // free → 254
  grid.Update({0, 0}, 0.1f);     // undecided → 205
  WriteOccupancyGridPgm(dir_ / "map.pgm", grid, {.margin_cells = 4});
  const OccupancyImage image = ReadOccupancyImage(dir_ / "map.yaml");

  EXPECT_EQ(image.width, 5 + 7 + 1 + 2 * 4);
  EXPECT_EQ(image.height, 12 + 3 + 1 + 2 * 4);
  EXPECT_EQ(image.resolution_m, 0.1);
  EXPECT_EQ(image.origin_m.x(), -11 * 0.1);
  EXPECT_EQ(image.origin_m.y(), -7 * 0.1);
  const std::string pgm = testing::ReadText(dir_ / "map.pgm");
  const std::size_t count = static_cast<std::size_t>(image.width) * image.height;
  ASSERT_EQ(image.pixels.size(), count);
  EXPECT_EQ(std::string(image.pixels.begin(), image.pixels.end()), pgm.substr(pgm.size() - count));
  EXPECT_EQ(PixelAt(image, grid.CellCenter({-7, 12})), 0);
  EXPECT_EQ(PixelAt(image, grid.CellCenter({5, -3})), 254);
  EXPECT_EQ(PixelAt(image, grid.CellCenter({0, 0})), 205);
  EXPECT_EQ(PixelAt(image, grid.CellCenter({1, 1})), 205);  // never written
}

TEST_F(MapReader, HeaderCommentsTwoNumberOriginAndOptionalKeys) {
  WriteFile("sub.pgm", "P5 # comment\n# another\n3\t2 255 " + Pgm(""));
  const auto yaml = WriteFile("sub.yaml",
                              "image: sub.pgm\nresolution: 0.25\norigin: [1, -2]\nnegate: 0\n"
                              "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n");
  const OccupancyImage image = ReadOccupancyImage(yaml);
  EXPECT_EQ(image.width, 3);
  EXPECT_EQ(image.height, 2);
  EXPECT_EQ(image.resolution_m, 0.25);
  EXPECT_EQ(image.origin_m, Eigen::Vector2d(1.0, -2.0));
  EXPECT_EQ(image.pixels, (std::vector<std::uint8_t>{0x00, 0xfe, 0xcd, 0x10, 0x20, 0x30}));
}

TEST_F(MapReader, SmallMaxvalIsScaledAndNegateFlips) {
  WriteFile("map.pgm", std::string("P5\n2 1\n15\n\x0f\x05", 12));
  WriteFile("map.yaml", "image: map.pgm\nresolution: 1\norigin: [0, 0, 0]\n");
  EXPECT_EQ(ReadOccupancyImage(dir_ / "map.yaml").pixels, (std::vector<std::uint8_t>{255, 85}));
  WriteFile("map.yaml", "image: map.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 1\n");
  EXPECT_EQ(ReadOccupancyImage(dir_ / "map.yaml").pixels, (std::vector<std::uint8_t>{0, 170}));
}

TEST_F(MapReader, AbsoluteImagePath) {
  WriteFile("elsewhere.pgm", Pgm());
  const auto yaml = WriteFile("abs.yaml", "image: " + (dir_ / "elsewhere.pgm").string() +
                                              "\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_EQ(ReadOccupancyImage(yaml).width, 3);
}

TEST_F(MapReader, TruncatedPixelsNameThePgm) {
  const auto yaml = WriteMap(Pgm().substr(0, Pgm().size() - 1));
  const std::string message = InputErrorOf([&] { ReadOccupancyImage(yaml); });
  EXPECT_TRUE(Contains(message, (dir_ / "map.pgm").string())) << message;
  EXPECT_TRUE(Contains(message, "truncated pixel data")) << message;
  EXPECT_TRUE(Contains(message, "6 bytes")) << message;
}

TEST_F(MapReader, BadMagicNamesThePgm) {
  for (const std::string header : {"P2\n3 2\n255\n", "P6\n3 2\n255\n", ""}) {
    const auto yaml = WriteMap(Pgm(header));
    const std::string message = InputErrorOf([&] { ReadOccupancyImage(yaml); });
    EXPECT_TRUE(Contains(message, (dir_ / "map.pgm").string())) << message;
    EXPECT_TRUE(Contains(message, "bad magic")) << message;
  }
}

TEST_F(MapReader, BadHeaderFieldsAreNamed) {
  const std::pair<std::string, std::string> cases[] = {
      {"P5\nx 2\n255\n", "'width'"},         {"P5\n3 0\n255\n", "'height'"},
      {"P5\n3 2\n65535\n", "16-bit"},        {"P5\n3 2\n", "'maxval'"},
      {"P5\n3 2\n0\n", "'maxval'"},          {"P5\n3 99999999999\n255\n", "'height'"},
      {"P5\n3 2\n15\n", "above maxval"}};  // 0xfe > 15
  for (const auto& [header, part] : cases) {
    const auto yaml = WriteMap(Pgm(header));
    const std::string message = InputErrorOf([&] { ReadOccupancyImage(yaml); });
    EXPECT_TRUE(Contains(message, "map.pgm")) << header;
    EXPECT_TRUE(Contains(message, part)) << header;
  }
}

// Issue 8 item 3: an image that is a directory or has a NUL byte let std::ios_base::failure
// escape (exit 1, no file name).
TEST_F(MapReader, ImageThatIsADirectoryOrHasANulByteNamesTheYaml) {
  WriteFile("map.pgm", Pgm());
  std::filesystem::create_directory(dir_ / "sub");
  const std::pair<std::string, std::string> cases[] = {
      {"image: .\n", "map.yaml:1: key 'image': '"},
      {"image: sub\n", "map.yaml:1: key 'image': '"},
      {"image: \"map\\0.pgm\"\n", "map.yaml:1: key 'image': contains a NUL byte"},
  };
  for (const auto& [image, part] : cases) {
    const auto yaml = WriteFile("map.yaml", image + "resolution: 0.1\norigin: [0, 0, 0]\n");
    const std::string message = InputErrorOf([&] { ReadOccupancyImage(yaml); });
    EXPECT_TRUE(Contains(message, part)) << image << message;
  }
  const auto yaml = WriteFile("map.yaml", "image: sub\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_TRUE(Contains(InputErrorOf([&] { ReadOccupancyImage(yaml); }), "is a directory"));
}

// Issue 8 item 5: an image of /dev/zero was read until memory ran out, a FIFO hung. Only a
// regular file, of at most a map's largest size, is read.
TEST_F(MapReader, DevicesFifosAndHugeImagesFailBeforeReading) {
  const std::string fifo = (dir_ / "fifo.pgm").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& image : {std::string("/dev/zero"), fifo}) {
    const auto yaml =
        WriteFile("map.yaml", "image: " + image + "\nresolution: 0.1\norigin: [0, 0, 0]\n");
    const std::string message = InputErrorOf([&] { ReadOccupancyImage(yaml); });
    EXPECT_TRUE(Contains(message, "not a regular file")) << image << ": " << message;
    EXPECT_TRUE(Contains(message, "map.yaml")) << message;
  }
  // A header promising more pixels than a map may have is refused before the pixels are read.
  const auto yaml = WriteMap(Pgm("P5\n20000 20000\n255\n"));
  EXPECT_TRUE(Contains(InputErrorOf([&] { ReadOccupancyImage(yaml); }), "20000 × 20000 pixels"));
}

// Issue 8 item 19: yaml-cpp's nesting limit was reported as "YAML syntax error: bad file".
TEST_F(MapReader, DeeplyNestedYamlNamesTheFileAndLine) {
  std::string block;  // one "- " per line, each indented further; the limit is hit on line 502
  for (int i = 0; i < 1000; ++i) block += std::string(2 * i + 2, ' ') + "- \n";
  const std::pair<std::string, std::string> cases[] = {
      {"origin: " + std::string(1000, '[') + std::string(1000, ']') + "\n", ":3: "},
      {"origin:\n" + block, ":502: "},
  };
  for (const auto& [origin, line] : cases) {
    const auto yaml = WriteFile("deep.yaml", "image: map.pgm\nresolution: 0.1\n" + origin);
    const std::string message = InputErrorOf([&] { ReadOccupancyImage(yaml); });
    EXPECT_TRUE(Contains(message, yaml.string() + line + "YAML nesting deeper than")) << message;
    EXPECT_FALSE(Contains(message, "bad file")) << message;
  }
}

TEST_F(MapReader, MissingResolutionNamesTheYamlAndKey) {
  const auto yaml = WriteMap(Pgm(), "", "");
  const std::string message = InputErrorOf([&] { ReadOccupancyImage(yaml); });
  EXPECT_TRUE(Contains(message, yaml.string())) << message;
  EXPECT_TRUE(Contains(message, "'resolution'")) << message;
  EXPECT_TRUE(Contains(message, "required")) << message;
}

TEST_F(MapReader, BadYamlValuesNameTheFileLineAndKey) {
  const std::pair<std::string, std::string> cases[] = {
      {"resolution: -0.1\n", "map.yaml:2: key 'resolution'"},
      {"resolution: fine\n", "map.yaml:2: key 'resolution'"},
      {"resolution: 0.1\nnegate: 2\n", "key 'negate'"},
      {"resolution: 0.1\nmode: raw\n", "key 'mode'"},
      {"resolution: 0.1\nfree_thresh: 1.5\n", "key 'free_thresh'"},
      {"resolution: 0.1\nresolutoin: 0.1\n", "unknown key 'resolutoin'"}};
  for (const auto& [resolution, part] : cases) {
    const auto yaml = WriteMap(Pgm(), "", resolution);
    const std::string message = InputErrorOf([&] { ReadOccupancyImage(yaml); });
    EXPECT_TRUE(Contains(message, part)) << message;
  }
  WriteFile("map.yaml", "image: map.pgm\nresolution: 0.1\norigin: [0, 0, 0.5]\n");
  EXPECT_TRUE(Contains(InputErrorOf([&] { ReadOccupancyImage(dir_ / "map.yaml"); }), "yaw"));
  WriteFile("map.yaml", "image: map.pgm\nresolution: 0.1\norigin: 3\n");
  EXPECT_TRUE(Contains(InputErrorOf([&] { ReadOccupancyImage(dir_ / "map.yaml"); }), "origin"));
  WriteFile("map.yaml", "image: [a\n");
  EXPECT_TRUE(Contains(InputErrorOf([&] { ReadOccupancyImage(dir_ / "map.yaml"); }), "syntax"));
}

TEST_F(MapReader, MissingFilesAreNamed) {
  EXPECT_TRUE(Contains(InputErrorOf([&] { ReadOccupancyImage(dir_ / "none.yaml"); }),
                       "none.yaml: cannot open file"));
  WriteFile("map.yaml", "image: gone.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n");
  EXPECT_TRUE(Contains(InputErrorOf([&] { ReadOccupancyImage(dir_ / "map.yaml"); }),
                       "gone.pgm: cannot open file"));
}

}  // namespace
}  // namespace slamkit
