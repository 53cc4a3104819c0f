#pragma once

// MathGL plumbing shared by the figure writers: output format and atomic writing, text escaping,
// data ranges and the frame around a plot box. Private to the report module.

#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <span>

#include <mgl2/mgl.h>

namespace slamkit::internal {

enum class ImageFormat { kPng, kSvg };

// The format named by the extension; also rejects a canvas without pixels.
ImageFormat CheckedFormat(const std::filesystem::path& path, int width_px, int height_px);

// Turns off MathGL's warning text: problems surface as exceptions, never as text on stderr.
void SuppressMglWarnings();

// Renders `gr` into a temporary file and renames it to `path`; a failure leaves neither.
void WriteAtomically(mglGraph& gr, const std::filesystem::path& path, ImageFormat format);

// MathGL reads TeX-like markup (_ ^ @ { } # \) in every string; user text must print verbatim.
std::string Escaped(std::string_view text);

// The span of the finite values added, widened by a margin so that nothing sits on the frame.
class Range {
 public:
  void Add(double v);
  void Add(const std::vector<double>& values);
  // [lo, hi] widened by `margin` of the span on each side and to at least `min_span`, or for a
  // constant series a tenth of its magnitude; [0, 1] when nothing was added.
  std::pair<double, double> Padded(double margin, double min_span) const;

 private:
  double lo_ = std::numeric_limits<double>::infinity();
  double hi_ = -std::numeric_limits<double>::infinity();
};

// Canvas fractions for one plot region: MathGL shrinks the box inside it to leave room for tick
// labels, so a region may reach past the canvas edges to keep the margins narrow.
struct Region {
  double x0, x1, y0, y1;
};

// Data limits of a plot box.
struct Box {
  mglPoint lo;
  mglPoint hi;
};

// Frame, grid, tick labels and axis labels for the current ranges; a null label is left out.
void DrawFrame(mglGraph& gr, const char* x_label, const char* y_label);

// Paired coordinates for one MathGL polyline or marker set (NaN breaks a polyline).
struct XyData {
  std::vector<double> x;
  std::vector<double> y;
  void Add(double px, double py) {
    x.push_back(px);
    y.push_back(py);
  }
  // Ends the current polyline: MathGL draws no segment across a NaN point.
  void Break() {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    Add(kNaN, kNaN);
  }
  bool Empty() const { return x.empty(); }
};

// Sets the data limits of the current region to cover `rx` × `ry` (each padded by 4 %, at least
// 1 m) at equal scale on both axes, widening the span so that the box is filled; returns them.
Box SetEqualScaleRanges(mglGraph& gr, const Range& rx, const Range& ry);

// The legend corner (MathGL's 0 bottom-left … 3 top-right) covering the fewest points of
// `layers` inside `box`; top right on ties.
int EmptiestCorner(std::span<const XyData* const> layers, const Box& box);

// `text` centred above the box spanning [lo, hi], `lift` box heights over its top edge (text is
// never clipped by the box, unlike lines).
void PutsAboveBox(mglGraph& gr, const Box& box, const std::string& text, double lift,
                  double size);

}  // namespace slamkit::internal
