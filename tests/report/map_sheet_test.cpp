#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "slamkit/io/grid_writers.hpp"
#include "slamkit/io/map_reader.hpp"
#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/report/figures.hpp"

#include "common/temp_dir.hpp"
#include "png_pixels.hpp"

namespace slamkit {
namespace {

namespace fs = std::filesystem;
using testing::ReadRgbaPng;
using testing::RgbaImage;

bool IsBlue(const std::uint8_t* p) { return p[2] > 180 && p[0] < 90 && p[1] < 90; }
bool IsRed(const std::uint8_t* p) { return p[0] > 180 && p[1] < 90 && p[2] < 90; }
bool IsDark(const std::uint8_t* p) { return p[0] < 90 && p[1] < 90 && p[2] < 90; }
bool IsUnknownGrey(const std::uint8_t* p) {  // the unknown fill, 0xBE
  return std::abs(p[0] - 0xBE) < 3 && p[0] == p[1] && p[1] == p[2];
}

// Pixels of `is` in columns [x0, x1) and rows [y0, y1).
int Count(const RgbaImage& image, bool (*is)(const std::uint8_t*), int x0, int x1, int y0,
          int y1) {
  int n = 0;
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) n += is(image.At(x, y)) ? 1 : 0;
  }
  return n;
}

// A 10 m × 6 m free room at the world origin with two one-cell walls: x ∈ [2, 2.05) for
// y ∈ [1, 5) and y ∈ [1, 1.05) for x ∈ [3, 9); written and read back through io, so that the
// sheet is checked against the map files a grid run leaves.
OccupancyImage RoomThroughIo(const fs::path& dir) {
  OccupancyGrid grid;
  for (int y = 0; y < 120; ++y) {
    for (int x = 0; x < 200; ++x) {
      const bool wall = (x == 40 && y >= 20 && y < 100) || (y == 20 && x >= 60 && x < 180);
      grid.Update({x, y}, wall ? 3.0f : -3.0f);
    }
  }
  WriteOccupancyGridPgm(dir / "map.pgm", grid);
  return ReadOccupancyImage(dir / "map.yaml");
}

Trajectory Segment(Eigen::Vector2d a, Eigen::Vector2d b) {
  Trajectory path;
  for (int i = 0; i <= 20; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (i / 20.0);
    path.push_back({0.1 * i, Pose2(p.x(), p.y(), 0.0)});
  }
  return path;
}

MapSheetData OnePanel(const OccupancyImage& map, Trajectory path) {
  MapSheetData data;
  data.panels.push_back({"room", map, std::move(path), {}, false});
  return data;
}

// The mean column (vertical) or row (horizontal) of the `is` pixels inside a window.
struct Window {
  int x0, x1, y0, y1;
};
double MeanPosition(const RgbaImage& image, bool (*is)(const std::uint8_t*), const Window& w,
                    bool column) {
  double sum = 0.0;
  int n = 0;
  for (int y = w.y0; y < w.y1; ++y) {
    for (int x = w.x0; x < w.x1; ++x) {
      if (!is(image.At(x, y))) continue;
      sum += column ? x : y;
      ++n;
    }
  }
  EXPECT_GT(n, 10);
  return n > 0 ? sum / n : -1.0;
}

class MapSheet : public testing::TempDirTest {};

TEST_F(MapSheet, WritesPngOfTheLayoutSizeAndSvg) {
  const OccupancyImage room = RoomThroughIo(dir_);
  MapSheetData data;
  data.title = "suite {grid} 100%";
  data.panel_px = 200;
  for (int i = 0; i < 5; ++i) {
    data.panels.push_back({"run " + std::to_string(i), room, Segment({1, 1}, {8, 5}),
                           Segment({1, 1}, {9, 4}), false});
  }
  WriteMapContactSheet(dir_ / "sheet.png", data);
  const RgbaImage image = ReadRgbaPng(dir_ / "sheet.png");
  EXPECT_EQ(image.width, 3 * 200);       // ceil(sqrt(5)) columns
  EXPECT_EQ(image.height, 2 * 200 + 48);  // two rows and the title band
  EXPECT_GT(Count(image, IsBlue, 0, image.width, 0, image.height), 5 * 50);
  EXPECT_GT(Count(image, IsUnknownGrey, 0, image.width, 0, image.height), 5 * 1000);
  // The sixth cell of the grid has no panel.
  EXPECT_EQ(Count(image, IsUnknownGrey, 400, 600, 248, 448), 0);
  data.columns = 5;
  WriteMapContactSheet(dir_ / "sheet.svg", data);
  EXPECT_GT(fs::file_size(dir_ / "sheet.svg"), 1000u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 4);
}

TEST_F(MapSheet, FailedPanelShowsNoMapBesideADrawnOne) {
  MapSheetData data = OnePanel(RoomThroughIo(dir_), Segment({1, 1}, {8, 5}));
  data.panels.push_back({"crashed", {}, {}, {}, true});
  data.panels.push_back({"failed with a map", data.panels[0].map, {}, {}, true});
  WriteMapContactSheet(dir_ / "sheet.png", data);
  const RgbaImage image = ReadRgbaPng(dir_ / "sheet.png");
  ASSERT_EQ(image.width, 2 * 400);
  ASSERT_EQ(image.height, 2 * 400);
  EXPECT_GT(Count(image, IsUnknownGrey, 0, 400, 0, 400), 5000);
  for (const Window& w : {Window{400, 800, 0, 400}, Window{0, 400, 400, 800}}) {
    EXPECT_LT(Count(image, IsUnknownGrey, w.x0, w.x1, w.y0, w.y1), 100);  // anti-aliased text
    EXPECT_GT(Count(image, IsRed, w.x0, w.x1, w.y0, w.y1), 30);  // "no map"
    EXPECT_GT(Count(image, IsDark, w.x0, w.x1, w.y0, w.y1), 300);  // frame and title
  }
}

// The path is drawn in the map's world frame: a segment along each wall covers the wall's pixels.
// The walls are asymmetric, so a flipped or shifted axis moves a wall away from its segment.
TEST_F(MapSheet, PathAlongAWallLandsOnTheWall) {
  const OccupancyImage room = RoomThroughIo(dir_);
  WriteMapContactSheet(dir_ / "map.png", OnePanel(room, {}));
  WriteMapContactSheet(dir_ / "vertical.png", OnePanel(room, Segment({2.025, 2}, {2.025, 4})));
  WriteMapContactSheet(dir_ / "horizontal.png", OnePanel(room, Segment({4, 1.025}, {8, 1.025})));
  const RgbaImage map = ReadRgbaPng(dir_ / "map.png");
  const RgbaImage vertical = ReadRgbaPng(dir_ / "vertical.png");
  const RgbaImage horizontal = ReadRgbaPng(dir_ / "horizontal.png");
  ASSERT_EQ(map.width, 400);
  const Window inner{20, 380, 40, 380};  // inside the frame, below the title
  const double path_x = MeanPosition(vertical, IsBlue, inner, true);
  const double path_y = MeanPosition(horizontal, IsBlue, inner, false);
  // The wall pixels in the rows (columns) the segment covers, away from the frame.
  const int y = static_cast<int>(MeanPosition(vertical, IsBlue, inner, false));
  const int x = static_cast<int>(MeanPosition(horizontal, IsBlue, inner, true));
  const double wall_x = MeanPosition(map, IsDark, {inner.x0, inner.x1, y - 10, y + 10}, true);
  const double wall_y = MeanPosition(map, IsDark, {x - 10, x + 10, inner.y0, inner.y1}, false);
  EXPECT_NEAR(path_x, wall_x, 1.5);
  EXPECT_NEAR(path_y, wall_y, 1.5);
  // The segments cover the walls: no wall pixel is left beside them.
  EXPECT_EQ(Count(vertical, IsDark, inner.x0, inner.x1, y - 10, y + 10), 0);
  EXPECT_EQ(Count(horizontal, IsDark, x - 10, x + 10, inner.y0, inner.y1), 0);
}

// Equal scale: the 10 m × 6 m of known cells keep their shape whatever the panel's box.
TEST_F(MapSheet, KnownAreaKeepsItsAspectRatio) {
  WriteMapContactSheet(dir_ / "map.png", OnePanel(RoomThroughIo(dir_), {}));
  const RgbaImage image = ReadRgbaPng(dir_ / "map.png");
  int x0 = image.width, x1 = -1, y0 = image.height, y1 = -1;
  for (int y = 40; y < image.height; ++y) {  // below the title
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.At(x, y);
      if (!(p[0] > 0xF0 && p[0] < 0xFF && p[0] == p[1] && p[1] == p[2])) continue;  // free fill
      x0 = std::min(x0, x);
      x1 = std::max(x1, x);
      y0 = std::min(y0, y);
      y1 = std::max(y1, y);
    }
  }
  ASSERT_GT(x1, x0);
  EXPECT_NEAR(static_cast<double>(x1 - x0 + 1) / (y1 - y0 + 1), 10.0 / 6.0, 0.03);
  EXPECT_GT(x1 - x0, 300);  // the map fills most of the 400-px panel
}

TEST_F(MapSheet, HugeMapKeepsAOneCellWall) {
  OccupancyImage map;
  map.width = map.height = 6000;
  map.pixels.assign(6000u * 6000u, 254);
  for (int row = 0; row < 6000; ++row) map.pixels[row * 6000u + 4500] = 0;
  WriteMapContactSheet(dir_ / "huge.png", OnePanel(map, {}));
  const RgbaImage image = ReadRgbaPng(dir_ / "huge.png");
  // 300 m across about 340 px: the wall is about 3/4 of the way right in every row.
  for (int y = 100; y < 300; y += 10) {
    EXPECT_GT(Count(image, IsDark, 240, 320, y, y + 1), 0) << "row " << y;
  }
}

TEST_F(MapSheet, BadInputIsRejectedWithoutAFile) {
  MapSheetData data;
  EXPECT_THROW(WriteMapContactSheet(dir_ / "empty.png", data), std::invalid_argument);
  data = OnePanel(RoomThroughIo(dir_), {});
  EXPECT_THROW(WriteMapContactSheet(dir_ / "sheet.pdf", data), std::invalid_argument);
  data.panel_px = 10;
  EXPECT_THROW(WriteMapContactSheet(dir_ / "small.png", data), std::invalid_argument);
  data.panel_px = 400;
  data.panels[0].map.pixels.pop_back();
  EXPECT_THROW(WriteMapContactSheet(dir_ / "torn.png", data), std::invalid_argument);
  for (const char* name : {"empty.png", "sheet.pdf", "small.png", "torn.png"}) {
    EXPECT_FALSE(fs::exists(dir_ / name)) << name;
  }
}

TEST_F(MapSheet, UnwritablePathThrowsNamingIt) {
  const fs::path path = dir_ / "no_such_dir" / "sheet.png";
  try {
    WriteMapContactSheet(path, OnePanel(RoomThroughIo(dir_), {}));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace slamkit
