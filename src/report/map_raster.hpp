#pragma once

// Occupancy images reduced to what a contact-sheet panel draws: pixels classified as map_server
// reads them, cropped to the known area and merged into blocks, so that MathGL gets a few hundred
// blocks per side whatever the size of the map. Private to the report module.

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "slamkit/maps/occupancy_image.hpp"

namespace slamkit::internal {

// Ordered so that the larger value wins when pixels are merged into a block.
enum class MapCell : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

// map_server's trinary reading with its default thresholds: p = (255 - pixel) / 255 is occupied
// above 0.65 and free below 0.196 (ReadOccupancyImage has already undone `negate`). io writes 0,
// 254 and 205, which read back as occupied, free and unknown.
MapCell ClassifyPixel(std::uint8_t pixel);

// A rectangle of image pixels, half-open; columns from the left, rows from the bottom (row 0 is
// the image's last row, the smallest y), so that world coordinates grow with both indices.
struct PixelBox {
  int col0 = 0;
  int row0 = 0;
  int col1 = 0;
  int row1 = 0;
  int width() const { return col1 - col0; }
  int height() const { return row1 - row0; }
  bool empty() const { return col1 <= col0 || row1 <= row0; }
};

// Throws std::invalid_argument unless pixels, width, height, resolution and origin agree.
void CheckImage(const OccupancyImage& image);

// The bounding box of the known (free or occupied) pixels; empty when there are none.
PixelBox KnownPixels(const OccupancyImage& image);

// World coordinates of the lower-left corner of pixel (col, row), rows from the bottom.
Eigen::Vector2d PixelCorner(const OccupancyImage& image, int col, int row);

// The pixel holding world point `p`, rows from the bottom (may lie outside the image).
Eigen::Vector2i WorldToPixel(const OccupancyImage& image, const Eigen::Vector2d& p);

// A coarse copy of part of an image: block (i, j) covers `block` × `block` pixels.
struct BlockRaster {
  int width = 0;   // blocks
  int height = 0;
  int block = 1;   // pixels per block side
  double block_m = 0.0;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // lower-left corner of block (0, 0)
  std::vector<MapCell> cells;                          // row-major, bottom row first
  MapCell At(int i, int j) const { return cells[static_cast<std::size_t>(j) * width + i]; }
};

// `box` (inside the image) in blocks of `block` pixels; the last row and column may reach past
// `box`, where pixels count as unknown. A block is occupied if any of its pixels is, else free if
// any is, else unknown, so that a one-pixel wall survives any factor. One pass over the pixels.
BlockRaster Downsample(const OccupancyImage& image, const PixelBox& box, int block);

// Blocks of equal cells merged into rectangles (runs along a row, stacked while the rows above
// repeat them): MathGL's time and an SVG's size grow with the number of shapes drawn.
struct BlockRect {
  int i0, j0, i1, j1;  // half-open block indices
  MapCell cell;
};
std::vector<BlockRect> MergedRects(const BlockRaster& raster, MapCell skip);

}  // namespace slamkit::internal
