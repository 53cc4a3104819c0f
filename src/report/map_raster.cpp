// Occupancy images classified, cropped and downsampled for the contact sheet.

#include "map_raster.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>

namespace slamkit::internal {
namespace {

// ClassifyPixel for every byte, so the downsampling pass is a lookup and a max per pixel.
std::array<MapCell, 256> ClassificationTable() {
  std::array<MapCell, 256> table{};
  for (int v = 0; v < 256; ++v) {
    const double p = (255.0 - v) / 255.0;
    table[v] = p > 0.65 ? MapCell::kOccupied : p < 0.196 ? MapCell::kFree : MapCell::kUnknown;
  }
  return table;
}

const std::array<MapCell, 256>& Table() {
  static const std::array<MapCell, 256> table = ClassificationTable();
  return table;
}

}  // namespace

MapCell ClassifyPixel(std::uint8_t pixel) { return Table()[pixel]; }

void CheckImage(const OccupancyImage& image) {
  if (image.width < 0 || image.height < 0 ||
      image.pixels.size() != static_cast<std::size_t>(image.width) * image.height) {
    throw std::invalid_argument("map contact sheet: pixel count is not width × height");
  }
  if (!(image.resolution_m > 0.0) || !std::isfinite(image.resolution_m) ||
      !image.origin_m.allFinite()) {
    throw std::invalid_argument("map contact sheet: bad map resolution or origin");
  }
}

PixelBox KnownPixels(const OccupancyImage& image) {
  PixelBox box{image.width, image.height, 0, 0};
  const std::array<MapCell, 256>& table = Table();
  for (int y = 0; y < image.height; ++y) {
    const std::uint8_t* line = &image.pixels[static_cast<std::size_t>(y) * image.width];
    const int row = image.height - 1 - y;
    for (int col = 0; col < image.width; ++col) {
      if (table[line[col]] == MapCell::kUnknown) continue;
      box.col0 = std::min(box.col0, col);
      box.col1 = std::max(box.col1, col + 1);
      box.row0 = std::min(box.row0, row);
      box.row1 = std::max(box.row1, row + 1);
    }
  }
  return box.empty() ? PixelBox{} : box;
}

Eigen::Vector2d PixelCorner(const OccupancyImage& image, int col, int row) {
  return image.origin_m + image.resolution_m * Eigen::Vector2d(col, row);
}

Eigen::Vector2i WorldToPixel(const OccupancyImage& image, const Eigen::Vector2d& p) {
  const Eigen::Vector2d q = (p - image.origin_m) / image.resolution_m;
  return {static_cast<int>(std::floor(q.x())), static_cast<int>(std::floor(q.y()))};
}

BlockRaster Downsample(const OccupancyImage& image, const PixelBox& box, int block) {
  if (block < 1) throw std::invalid_argument("map contact sheet: block size must be positive");
  BlockRaster raster;
  raster.block = block;
  raster.width = (box.width() + block - 1) / block;
  raster.height = (box.height() + block - 1) / block;
  raster.block_m = block * image.resolution_m;
  raster.origin_m = PixelCorner(image, box.col0, box.row0);
  raster.cells.assign(static_cast<std::size_t>(raster.width) * raster.height, MapCell::kUnknown);
  const std::array<MapCell, 256>& table = Table();
  for (int row = box.row0; row < box.row1; ++row) {
    const std::uint8_t* line =
        &image.pixels[static_cast<std::size_t>(image.height - 1 - row) * image.width];
    MapCell* out = &raster.cells[static_cast<std::size_t>((row - box.row0) / block) * raster.width];
    for (int col = box.col0; col < box.col1; ++col) {
      MapCell& cell = out[(col - box.col0) / block];
      cell = std::max(cell, table[line[col]]);
    }
  }
  return raster;
}

std::vector<BlockRect> MergedRects(const BlockRaster& raster, MapCell skip) {
  std::vector<BlockRect> done;
  std::vector<BlockRect> open;  // rectangles reaching the previous row, by increasing i0
  std::vector<BlockRect> next;
  for (int j = 0; j < raster.height; ++j) {
    next.clear();
    std::size_t k = 0;
    for (int i = 0; i < raster.width;) {
      const MapCell cell = raster.At(i, j);
      int end = i + 1;
      while (end < raster.width && raster.At(end, j) == cell) ++end;
      if (cell != skip) {
        while (k < open.size() && open[k].i0 < i) done.push_back(open[k++]);
        const bool grows = k < open.size() && open[k].i0 == i && open[k].i1 == end &&
                           open[k].cell == cell;
        if (grows) {
          next.push_back(open[k++]);
          next.back().j1 = j + 1;
        } else {
          next.push_back({i, j, end, j + 1, cell});
        }
      }
      i = end;
    }
    done.insert(done.end(), open.begin() + static_cast<std::ptrdiff_t>(k), open.end());
    open.swap(next);
  }
  done.insert(done.end(), open.begin(), open.end());
  return done;
}

}  // namespace slamkit::internal
