#include "map_raster.hpp"

#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "slamkit/core/rng.hpp"

namespace slamkit::internal {
namespace {

// A width × height image of one value, 5 cm pixels, origin (-1, 2).
OccupancyImage Uniform(int width, int height, std::uint8_t value) {
  OccupancyImage image;
  image.width = width;
  image.height = height;
  image.pixels.assign(static_cast<std::size_t>(width) * height, value);
  image.origin_m = Eigen::Vector2d(-1.0, 2.0);
  return image;
}

// Pixel (col, row) with rows counted from the bottom, as the raster functions count them.
std::uint8_t& Pixel(OccupancyImage& image, int col, int row) {
  return image.pixels[static_cast<std::size_t>(image.height - 1 - row) * image.width + col];
}

TEST(MapRaster, ClassifiesAsMapServerWithDefaultThresholds) {
  EXPECT_EQ(ClassifyPixel(0), MapCell::kOccupied);    // what io writes for occupied
  EXPECT_EQ(ClassifyPixel(254), MapCell::kFree);      // free
  EXPECT_EQ(ClassifyPixel(205), MapCell::kUnknown);   // unknown
  EXPECT_EQ(ClassifyPixel(89), MapCell::kOccupied);   // p = 0.651
  EXPECT_EQ(ClassifyPixel(90), MapCell::kUnknown);    // p = 0.647
  EXPECT_EQ(ClassifyPixel(206), MapCell::kFree);      // p = 0.192
}

TEST(MapRaster, KnownPixelsCountRowsFromTheBottom) {
  OccupancyImage image = Uniform(40, 30, 205);
  EXPECT_TRUE(KnownPixels(image).empty());
  image.pixels[3] = 0;                 // top row, column 3
  Pixel(image, 10, 4) = 254;
  const PixelBox box = KnownPixels(image);
  EXPECT_EQ(box.col0, 3);
  EXPECT_EQ(box.col1, 11);
  EXPECT_EQ(box.row0, 4);
  EXPECT_EQ(box.row1, 30);
}

TEST(MapRaster, WorldAndPixelCornersAgree) {
  const OccupancyImage image = Uniform(40, 30, 205);
  EXPECT_TRUE(PixelCorner(image, 0, 0).isApprox(Eigen::Vector2d(-1.0, 2.0)));
  EXPECT_TRUE(PixelCorner(image, 40, 30).isApprox(Eigen::Vector2d(1.0, 3.5)));
  EXPECT_EQ(WorldToPixel(image, Eigen::Vector2d(-0.974, 2.001)), Eigen::Vector2i(0, 0));
  EXPECT_EQ(WorldToPixel(image, Eigen::Vector2d(0.26, 3.49)), Eigen::Vector2i(25, 29));
}

TEST(MapRaster, DownsamplingKeepsAOneCellWall) {
  OccupancyImage image = Uniform(6000, 6000, 254);
  for (int r = 0; r < 6000; ++r) Pixel(image, 3001, r) = 0;
  for (int c = 0; c < 6000; ++c) Pixel(image, c, 17) = 0;
  const BlockRaster raster = Downsample(image, KnownPixels(image), 16);
  ASSERT_EQ(raster.width, 375);
  ASSERT_EQ(raster.height, 375);
  EXPECT_DOUBLE_EQ(raster.block_m, 0.8);
  EXPECT_TRUE(raster.origin_m.isApprox(image.origin_m));
  for (int j = 0; j < raster.height; ++j) {
    for (int i = 0; i < raster.width; ++i) {
      const bool wall = i == 3001 / 16 || j == 1;
      ASSERT_EQ(raster.At(i, j), wall ? MapCell::kOccupied : MapCell::kFree) << i << ", " << j;
    }
  }
}

TEST(MapRaster, BlocksPreferOccupiedThenFreeAndCropToTheBox) {
  OccupancyImage image = Uniform(9, 7, 205);
  // The box below starts at pixel (1, 1): block (i, j) covers columns 1 + 3i … 3 + 3i.
  Pixel(image, 4, 4) = 254;  // block (1, 1): free among unknown
  Pixel(image, 7, 2) = 254;  // block (2, 0): free and occupied
  Pixel(image, 8, 1) = 0;
  Pixel(image, 0, 2) = 0;    // left of the box: not in any block
  const PixelBox box{1, 1, 9, 7};
  const BlockRaster raster = Downsample(image, box, 3);
  ASSERT_EQ(raster.width, 3);  // 8 columns: the last block reaches one past the box
  ASSERT_EQ(raster.height, 2);
  EXPECT_TRUE(raster.origin_m.isApprox(PixelCorner(image, 1, 1)));
  EXPECT_EQ(raster.At(0, 0), MapCell::kUnknown);
  EXPECT_EQ(raster.At(1, 1), MapCell::kFree);
  EXPECT_EQ(raster.At(2, 0), MapCell::kOccupied);
  EXPECT_EQ(raster.At(2, 1), MapCell::kUnknown);
}

TEST(MapRaster, MergedRectanglesCoverEveryKnownBlockOnce) {
  Rng rng(5);
  BlockRaster raster;
  raster.width = 37;
  raster.height = 23;
  for (int k = 0; k < raster.width * raster.height; ++k) {
    // Mostly long runs, as in a map, with noise so that rectangles split.
    const double u = rng.Uniform(0.0, 1.0);
    const MapCell previous = raster.cells.empty() ? MapCell::kFree : raster.cells.back();
    raster.cells.push_back(u < 0.8   ? previous
                           : u < 0.9 ? MapCell::kOccupied
                           : u < 0.95 ? MapCell::kFree
                                      : MapCell::kUnknown);
  }
  std::vector<int> covered(raster.cells.size(), 0);
  const std::vector<BlockRect> rects = MergedRects(raster, MapCell::kUnknown);
  for (const BlockRect& r : rects) {
    for (int j = r.j0; j < r.j1; ++j) {
      for (int i = r.i0; i < r.i1; ++i) {
        EXPECT_EQ(raster.At(i, j), r.cell);
        ++covered[static_cast<std::size_t>(j) * raster.width + i];
      }
    }
  }
  for (std::size_t k = 0; k < covered.size(); ++k) {
    EXPECT_EQ(covered[k], raster.cells[k] == MapCell::kUnknown ? 0 : 1) << k;
  }
  EXPECT_LT(rects.size(), raster.cells.size() / 3);
}

TEST(MapRaster, InconsistentImagesAreRejected) {
  OccupancyImage image = Uniform(4, 3, 205);
  EXPECT_NO_THROW(CheckImage(image));
  image.pixels.pop_back();
  EXPECT_THROW(CheckImage(image), std::invalid_argument);
  image = Uniform(4, 3, 205);
  image.resolution_m = 0.0;
  EXPECT_THROW(CheckImage(image), std::invalid_argument);
}

}  // namespace
}  // namespace slamkit::internal
