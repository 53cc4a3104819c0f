#pragma once

// A PNG decoded to 8-bit RGBA for tests that look at what a figure drew where.

#include <cstdint>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <png.h>

namespace slamkit::testing {

// Rows from the top, as in the file.
struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
  const std::uint8_t* At(int x, int y) const {
    return &rgba[4 * (static_cast<std::size_t>(y) * width + x)];
  }
};

inline RgbaImage ReadRgbaPng(const std::filesystem::path& path) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    ADD_FAILURE() << path << ": " << png.message;
    return {};
  }
  png.format = PNG_FORMAT_RGBA;
  RgbaImage image{static_cast<int>(png.width), static_cast<int>(png.height), {}};
  image.rgba.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgba.data(), 0, nullptr)) {
    ADD_FAILURE() << path << ": " << png.message;
    png_image_free(&png);
    return {};
  }
  return image;
}

}  // namespace slamkit::testing
