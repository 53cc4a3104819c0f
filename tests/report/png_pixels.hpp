#pragma once

// PNGs for the figure tests: decoded to 8-bit RGBA to look at what a figure drew where, their
// size read from the header, images written back, and the check that an image is a drawn figure.

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
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

struct PngSize {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
};

// The image size from the IHDR chunk, which the PNG standard requires to come first.
inline PngSize ReadPngSize(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::array<unsigned char, 24> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  EXPECT_EQ(in.gcount(), 24) << path;
  const std::array<unsigned char, 8> signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(std::equal(signature.begin(), signature.end(), head.begin())) << path;
  EXPECT_EQ(std::string(head.begin() + 12, head.begin() + 16), "IHDR") << path;
  const auto big_endian = [](const unsigned char* b) {
    return (std::uint32_t{b[0]} << 24) | (std::uint32_t{b[1]} << 16) |
           (std::uint32_t{b[2]} << 8) | std::uint32_t{b[3]};
  };
  return {big_endian(&head[16]), big_endian(&head[20])};
}

inline void WriteRgbaPng(const std::filesystem::path& path, const RgbaImage& image) {
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGBA;
  ASSERT_TRUE(png_image_write_to_file(&png, path.c_str(), 0, image.rgba.data(), 0, nullptr))
      << png.message;
}

inline RgbaImage Filled(int width, int height, std::array<std::uint8_t, 4> colour) {
  RgbaImage image{width, height, {}};
  for (int i = 0; i < width * height; ++i) {
    image.rgba.insert(image.rgba.end(), colour.begin(), colour.end());
  }
  return image;
}

// Why `image` is not a drawn figure, or "" if it looks like one: a figure has several distinct
// colours (lines, markers, text, anti-aliasing) and at least 1 % of its pixels differ from the
// background (its most common colour).
inline std::string NotADrawnFigure(const RgbaImage& image) {
  if (image.width == 0 || image.height == 0) return "no pixels";
  std::map<std::uint32_t, int> count;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.At(x, y);
      ++count[(std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) |
              (std::uint32_t{p[2]} << 8) | std::uint32_t{p[3]}];
    }
  }
  if (count.size() < 8) return std::to_string(count.size()) + " distinct colours";
  int background = 0;
  for (const auto& [colour, n] : count) background = std::max(background, n);
  const int total = image.width * image.height;
  if (total - background < total / 100) {
    return std::to_string(total - background) + " of " + std::to_string(total) +
           " pixels drawn";
  }
  return "";
}

}  // namespace slamkit::testing
