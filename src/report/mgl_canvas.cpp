#include "mgl_canvas.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <system_error>

#include <png.h>

namespace slamkit::internal {
namespace {

namespace fs = std::filesystem;

// A temporary name beside `path`, unique across threads and processes, with the same extension.
fs::path TemporaryPathBeside(const fs::path& path) {
  std::random_device entropy;
  char suffix[32];
  std::snprintf(suffix, sizeof(suffix), ".tmp-%08x%08x", entropy(), entropy());
  std::string name = ".";
  name += path.filename().string();
  name += suffix;
  name += path.extension().string();
  return path.parent_path() / name;
}

}  // namespace

ImageFormat CheckedFormat(const fs::path& path, int width_px, int height_px) {
  if (width_px <= 0 || height_px <= 0) {
    throw std::invalid_argument("figure " + path.string() + ": width and height must be positive");
  }
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".png") return ImageFormat::kPng;
  if (ext == ".svg") return ImageFormat::kSvg;
  throw std::invalid_argument("figure " + path.string() + ": extension must be .png or .svg");
}

void SuppressMglWarnings() { mglGraph::SuppressWarn(true); }

// The canvas's pixels encoded by libpng for speed (PNG_IMAGE_FLAG_FAST): the same image as
// MathGL's own PNG writer, which compresses harder and took a third of a map figure's time.
bool WriteFastPng(mglGraph& gr, const fs::path& path) {
  const unsigned char* rgb = gr.GetRGB();
  if (rgb == nullptr) return false;
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(gr.GetWidth());
  png.height = static_cast<png_uint_32>(gr.GetHeight());
  png.format = PNG_FORMAT_RGB;
  png.flags = PNG_IMAGE_FLAG_FAST;
  const bool ok = png_image_write_to_file(&png, path.c_str(), 0, rgb, 0, nullptr) != 0;
  png_image_free(&png);
  return ok;
}

void WriteAtomically(mglGraph& gr, const fs::path& path, ImageFormat format) {
  const fs::path tmp = TemporaryPathBeside(path);
  gr.SetWarn(mglWarnNone, "");
  bool encoded = true;
  if (format == ImageFormat::kPng) {
    encoded = WriteFastPng(gr, tmp);
  } else {
    gr.WriteSVG(tmp.c_str());
  }
  std::error_code ec;
  const bool written = encoded && gr.GetWarn() != mglWarnOpen && fs::is_regular_file(tmp, ec) &&
                       fs::file_size(tmp, ec) > 0 && !ec;
  if (written) fs::rename(tmp, path, ec);
  if (!written || ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write figure " + path.string());
  }
}

std::string Escaped(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (std::string_view("\\_^@{}#").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

void Range::Add(double v) {
  if (!std::isfinite(v)) return;
  lo_ = std::min(lo_, v);
  hi_ = std::max(hi_, v);
}

void Range::Add(const std::vector<double>& values) {
  for (const double v : values) Add(v);
}

std::pair<double, double> Range::Padded(double margin, double min_span) const {
  if (lo_ > hi_) return {0.0, 1.0};
  const double center = 0.5 * (lo_ + hi_);
  const double span = hi_ - lo_;
  const double floor = span > 0.0 ? min_span : std::max(min_span, 0.1 * std::abs(center));
  const double half = 0.5 * std::max(span * (1.0 + 2.0 * margin), floor);
  return {center - half, center + half};
}

void DrawFrame(mglGraph& gr, const char* x_label, const char* y_label) {
  gr.SetTickRotate(false);
  gr.Grid("xy", "{h7}");
  gr.Box();
  gr.Axis("xy");
  if (x_label != nullptr) gr.Label('x', x_label, 0);
  if (y_label != nullptr) gr.Label('y', y_label, 0, "value 0.3");  // clear of wide ticks
}

Box SetEqualScaleRanges(mglGraph& gr, const Range& rx, const Range& ry) {
  gr.SetRanges(0.0, 1.0, 0.0, 1.0);
  const mglPoint corner0 = gr.CalcScr(mglPoint(0.0, 0.0));
  const mglPoint corner1 = gr.CalcScr(mglPoint(1.0, 1.0));
  const double box_aspect = (corner1.x - corner0.x) / (corner1.y - corner0.y);
  const auto [x0, x1] = rx.Padded(0.04, 1.0);
  const auto [y0, y1] = ry.Padded(0.04, 1.0);
  const double half_x = 0.5 * std::max(x1 - x0, (y1 - y0) * box_aspect);
  const double half_y = half_x / box_aspect;
  const mglPoint center(0.5 * (x0 + x1), 0.5 * (y0 + y1));
  const Box box{mglPoint(center.x - half_x, center.y - half_y),
                mglPoint(center.x + half_x, center.y + half_y)};
  gr.SetRanges(box.lo, box.hi);
  return box;
}

int EmptiestCorner(std::span<const XyData* const> layers, const Box& box) {
  std::array<int, 4> count{};
  for (const XyData* xy : layers) {
    for (std::size_t i = 0; i < xy->x.size(); ++i) {
      const double u = (xy->x[i] - box.lo.x) / (box.hi.x - box.lo.x);
      const double v = (xy->y[i] - box.lo.y) / (box.hi.y - box.lo.y);
      if (u > 0.35 && u < 0.65) continue;
      if (v > 0.3 && v < 0.7) continue;
      ++count[(u >= 0.5 ? 1 : 0) + (v >= 0.5 ? 2 : 0)];
    }
  }
  const int corners[] = {3, 2, 1, 0};  // preference on ties: top right first
  return *std::min_element(std::begin(corners), std::end(corners),
                           [&](int a, int b) { return count[a] < count[b]; });
}

void PutsAboveBox(mglGraph& gr, const Box& box, const std::string& text, double lift,
                  double size) {
  const double x = 0.5 * (box.lo.x + box.hi.x);
  const double y = box.hi.y + lift * (box.hi.y - box.lo.y);
  gr.Puts(mglPoint(x, y), text.c_str(), ":C", size);
}

}  // namespace slamkit::internal
