// The contact sheet of occupancy-grid maps: one small panel per run, so a broken map stands out.

#include "slamkit/report/figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include <mgl2/mgl.h>

#include "map_raster.hpp"
#include "mgl_canvas.hpp"

namespace slamkit {
namespace {

using internal::BlockRaster;
using internal::BlockRect;
using internal::Box;
using internal::MapCell;
using internal::PixelBox;
using internal::Range;
using internal::Region;

// Layout, tuned by eye on 400-px panels (MathGL scales fonts with the region's size).
constexpr int kTitleBandPx = 48;        // the sheet's title
constexpr double kPanelTitle = 0.09;    // of a panel, above its box
constexpr double kPanelMargin = 0.035;  // of a panel, around its box
constexpr double kFontSize = 2.6;
constexpr double kViewMargin = 0.04;    // of the view's span, around map and path
constexpr double kMinViewSpanM = 1.0;
// Output pixels per block: about one keeps walls thin and sharp, and merged into rectangles the
// blocks are still few shapes for MathGL.
constexpr double kPixelsPerBlock = 1.0;

// Depths: MathGL draws larger z in front. Plot without z draws at the bottom of the range.
constexpr double kUnknownZ = -1.0;
constexpr double kKnownZ = -0.9;
constexpr double kOverlayZ = -0.8;
constexpr double kSecondaryPathZ = 0.3;
constexpr double kPathZ = 0.5;
constexpr double kFrameZ = 0.8;

const char* CellColour(MapCell cell) {
  switch (cell) {
    case MapCell::kOccupied: return "{x262626}";
    case MapCell::kFree: return "{xFAFAFA}";
    case MapCell::kUnknown: break;
  }
  return "{xBEBEBE}";
}
// An overlay's cells (predicted structure): light and dark orange.
const char* OverlayColour(MapCell cell) {
  return cell == MapCell::kOccupied ? "{xD95F02}" : "{xFDD9B5}";
}
constexpr const char* kPathPen = "b-2";
constexpr const char* kSecondaryPathPen = "{r6}-1";

struct Layout {
  int columns = 1;
  int rows = 1;
  int width_px = 0;
  int height_px = 0;
  int title_px = 0;
  int panel_px = 0;
  double box_factor_x = 1.0;  // MathGL's box over its InPlot region, per axis
  double box_factor_y = 1.0;
};

Layout ChooseLayout(const MapSheetData& data) {
  const int n = static_cast<int>(data.panels.size());
  if (n == 0) throw std::invalid_argument("map contact sheet: no panel");
  if (data.columns < 0) throw std::invalid_argument("map contact sheet: negative columns");
  if (data.panel_px < 50) throw std::invalid_argument("map contact sheet: panel_px below 50");
  Layout l;
  l.columns = data.columns > 0 ? std::min(data.columns, n)
                               : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  l.rows = (n + l.columns - 1) / l.columns;
  l.title_px = data.title.empty() ? 0 : kTitleBandPx;
  l.panel_px = data.panel_px;
  l.width_px = l.columns * data.panel_px;
  l.height_px = l.rows * data.panel_px + l.title_px;
  return l;
}

// MathGL shrinks the box inside an InPlot region (to leave room for ticks); measured once so that
// boxes can be put exactly where the layout wants them.
void MeasureBoxFactor(mglGraph& gr, Layout* l) {
  gr.InPlot(0.0, 1.0, 0.0, 1.0, false);
  gr.SetRanges(0.0, 1.0, 0.0, 1.0);
  const mglPoint c0 = gr.CalcScr(mglPoint(0.0, 0.0));
  const mglPoint c1 = gr.CalcScr(mglPoint(1.0, 1.0));
  l->box_factor_x = std::clamp(std::abs(c1.x - c0.x) / l->width_px, 0.1, 1.0);
  l->box_factor_y = std::clamp(std::abs(c1.y - c0.y) / l->height_px, 0.1, 1.0);
}

// Makes `box` (canvas fractions, y upwards) the current plot box.
void PlaceBox(mglGraph& gr, const Layout& l, const Region& box) {
  const double cx = 0.5 * (box.x0 + box.x1);
  const double cy = 0.5 * (box.y0 + box.y1);
  const double hx = 0.5 * (box.x1 - box.x0) / l.box_factor_x;
  const double hy = 0.5 * (box.y1 - box.y0) / l.box_factor_y;
  gr.InPlot(cx - hx, cx + hx, cy - hy, cy + hy, false);
}

// Panel `k`'s box in canvas fractions: below its title, inside a margin.
Region PanelBox(const Layout& l, int k) {
  const double p = l.panel_px;
  const double left = (k % l.columns) * p;
  const double top = l.title_px + (k / l.columns) * p;  // pixels from the canvas top
  const auto x = [&](double px) { return px / l.width_px; };
  const auto y = [&](double px) { return 1.0 - px / l.height_px; };
  return {x(left + kPanelMargin * p), x(left + (1.0 - kPanelMargin) * p),
          y(top + (1.0 - kPanelMargin) * p), y(top + kPanelTitle * p)};
}

// Data limits at equal scale on both axes, widened from the view to the box's shape.
Box SetEqualScale(mglGraph& gr, const Range& rx, const Range& ry, double box_w_px,
                  double box_h_px) {
  const double aspect = box_w_px / box_h_px;
  const auto [x0, x1] = rx.Padded(kViewMargin, kMinViewSpanM);
  const auto [y0, y1] = ry.Padded(kViewMargin, kMinViewSpanM);
  const double half_x = 0.5 * std::max(x1 - x0, (y1 - y0) * aspect);
  const double half_y = half_x / aspect;
  const double cx = 0.5 * (x0 + x1);
  const double cy = 0.5 * (y0 + y1);
  gr.SetRanges(cx - half_x, cx + half_x, cy - half_y, cy + half_y, -1.0, 1.0);
  return {mglPoint(cx - half_x, cy - half_y), mglPoint(cx + half_x, cy + half_y)};
}

void FillRect(mglGraph& gr, double x0, double y0, double x1, double y1, double z,
              const char* colour) {
  gr.Face(mglPoint(x0, y0, z), mglPoint(x1, y0, z), mglPoint(x0, y1, z), mglPoint(x1, y1, z),
          colour);
}

// A one-pixel frame of thin rectangles: MathGL's Box and lines cost tens of ms each, faces
// almost nothing.
void DrawFrame(mglGraph& gr, const Box& box, double px_m) {
  const mglPoint& a = box.lo;
  const mglPoint& b = box.hi;
  FillRect(gr, a.x, a.y, b.x, a.y + px_m, kFrameZ, "k");
  FillRect(gr, a.x, b.y - px_m, b.x, b.y, kFrameZ, "k");
  FillRect(gr, a.x, a.y, a.x + px_m, b.y, kFrameZ, "k");
  FillRect(gr, b.x - px_m, a.y, b.x, b.y, kFrameZ, "k");
}

// The known rectangles of a raster at depth z, coloured by `colour`.
void DrawKnown(mglGraph& gr, const BlockRaster& raster, double z,
               const char* (*colour)(MapCell)) {
  const double s = raster.block_m;
  const Eigen::Vector2d& o = raster.origin_m;
  for (const BlockRect& r : internal::MergedRects(raster, MapCell::kUnknown)) {
    FillRect(gr, o.x() + r.i0 * s, o.y() + r.j0 * s, o.x() + r.i1 * s, o.y() + r.j1 * s, z,
             colour(r.cell));
  }
}

// Unknown everywhere in the box, then the known rectangles over it.
void DrawRaster(mglGraph& gr, const BlockRaster& raster, const Box& box) {
  FillRect(gr, box.lo.x, box.lo.y, box.hi.x, box.hi.y, kUnknownZ, CellColour(MapCell::kUnknown));
  DrawKnown(gr, raster, kKnownZ, CellColour);
}

void DrawPath(mglGraph& gr, const Trajectory& path, double z, const char* pen) {
  if (path.empty()) return;
  const long n = static_cast<long>(path.size());
  mglData x(n);
  mglData y(n);
  mglData depth(n);
  for (long i = 0; i < n; ++i) {
    x.a[i] = path[i].pose.x();
    y.a[i] = path[i].pose.y();
    depth.a[i] = z;
  }
  gr.Plot(x, y, depth, pen);
}

// A bar of 1, 2 or 5 × 10^k metres, at most a quarter of the box wide, in its lower left.
void DrawScaleBar(mglGraph& gr, const Box& box, double px_m) {
  const double width = box.hi.x - box.lo.x;
  const double decade = std::pow(10.0, std::floor(std::log10(0.25 * width)));
  double length = decade;
  for (const double f : {2.0, 5.0}) {
    if (f * decade <= 0.25 * width) length = f * decade;
  }
  const double x0 = box.lo.x + 12.0 * px_m;
  const double y0 = box.lo.y + 10.0 * px_m;
  FillRect(gr, x0, y0, x0 + length, y0 + 3.0 * px_m, kFrameZ, "k");
  char label[32];
  std::snprintf(label, sizeof(label), "%g m", length);
  gr.Puts(mglPoint(x0 + 0.5 * length, y0 + 12.0 * px_m, kFrameZ), label, ":C", -0.9);
}

void DrawTitle(mglGraph& gr, const Box& box, double px_m, const std::string& title) {
  if (title.empty()) return;
  const mglPoint at(0.5 * (box.lo.x + box.hi.x), box.hi.y + 14.0 * px_m, kFrameZ);
  gr.Puts(at, internal::Escaped(title).c_str(), ":C", -1.2);
}

// The box's limits at 1 m per box pixel: "no map" needs no data.
Box SetPixelScale(mglGraph& gr, double box_w_px, double box_h_px) {
  gr.SetRanges(0.0, box_w_px, 0.0, box_h_px, -1.0, 1.0);
  return {mglPoint(0.0, 0.0), mglPoint(box_w_px, box_h_px)};
}

void DrawFailedPanel(mglGraph& gr, const MapSheetPanel& panel, double box_w_px,
                     double box_h_px) {
  const Box box = SetPixelScale(gr, box_w_px, box_h_px);
  DrawFrame(gr, box, 1.0);
  gr.Puts(mglPoint(0.5 * box_w_px, 0.5 * box_h_px, kFrameZ), "no map", "r:C", -2.0);
  DrawTitle(gr, box, 1.0, panel.title);
}

// The map cropped to its known area and the path, the paths over it, the frame and the labels.
void DrawMapPanel(mglGraph& gr, const MapSheetPanel& panel, double box_w_px, double box_h_px) {
  const OccupancyImage& map = panel.map;
  const PixelBox known = internal::KnownPixels(map);
  Range rx;
  Range ry;
  const auto add = [&](const Eigen::Vector2d& p) {
    rx.Add(p.x());
    ry.Add(p.y());
  };
  if (!known.empty()) {
    add(internal::PixelCorner(map, known.col0, known.row0));
    add(internal::PixelCorner(map, known.col1, known.row1));
  }
  const PixelBox overlay_known = internal::KnownPixels(panel.overlay);
  if (!overlay_known.empty()) {
    add(internal::PixelCorner(panel.overlay, overlay_known.col0, overlay_known.row0));
    add(internal::PixelCorner(panel.overlay, overlay_known.col1, overlay_known.row1));
  }
  for (const StampedPose& p : panel.path) add(p.pose.translation());
  if (known.empty() && panel.path.empty()) {  // all unknown: show the whole image
    add(map.origin_m);
    add(internal::PixelCorner(map, map.width, map.height));
  }
  const Box box = SetEqualScale(gr, rx, ry, box_w_px, box_h_px);
  const double px_m = (box.hi.x - box.lo.x) / box_w_px;
  const int block =
      std::max(1, static_cast<int>(std::ceil(px_m * kPixelsPerBlock / map.resolution_m - 1e-9)));
  DrawRaster(gr, internal::Downsample(map, known, block), box);
  if (!overlay_known.empty()) {
    DrawKnown(gr, internal::Downsample(panel.overlay, overlay_known, block), kOverlayZ,
              OverlayColour);
  }
  DrawPath(gr, panel.secondary_path, kSecondaryPathZ, kSecondaryPathPen);
  DrawPath(gr, panel.path, kPathZ, kPathPen);
  DrawFrame(gr, box, px_m);
  DrawScaleBar(gr, box, px_m);
  DrawTitle(gr, box, px_m, panel.title);
}

// The sheet's title centred in the band above the panels, in a panel-sized box so that its font
// matches the panels'.
void DrawSheetTitle(mglGraph& gr, const Layout& l, const std::string& title) {
  const double hx = 0.5 * l.panel_px / l.width_px;
  const double hy = 0.5 * l.panel_px / l.height_px;
  const double cy = 1.0 - 0.5 * l.title_px / l.height_px;
  PlaceBox(gr, l, {0.5 - hx, 0.5 + hx, cy - hy, cy + hy});
  gr.SetRanges(0.0, 1.0, 0.0, 1.0);
  gr.Puts(mglPoint(0.5, 0.5), internal::Escaped(title).c_str(), ":C", -1.6);
}

}  // namespace

void WriteMapContactSheet(const std::filesystem::path& path, const MapSheetData& data) {
  Layout layout = ChooseLayout(data);
  const internal::ImageFormat format =
      internal::CheckedFormat(path, layout.width_px, layout.height_px);
  for (const MapSheetPanel& panel : data.panels) {
    internal::CheckImage(panel.map);
    if (!panel.overlay.pixels.empty()) internal::CheckImage(panel.overlay);
  }
  internal::SuppressMglWarnings();
  mglGraph gr(0, layout.width_px, layout.height_px);
  gr.SetFontSize(kFontSize);
  MeasureBoxFactor(gr, &layout);
  for (std::size_t k = 0; k < data.panels.size(); ++k) {
    const MapSheetPanel& panel = data.panels[k];
    const Region box = PanelBox(layout, static_cast<int>(k));
    PlaceBox(gr, layout, box);
    const double w = (box.x1 - box.x0) * layout.width_px;
    const double h = (box.y1 - box.y0) * layout.height_px;
    if (panel.failed || panel.map.width == 0 || panel.map.height == 0) {
      DrawFailedPanel(gr, panel, w, h);
    } else {
      DrawMapPanel(gr, panel, w, h);
    }
  }
  if (layout.title_px > 0) DrawSheetTitle(gr, layout, data.title);
  internal::WriteAtomically(gr, path, format);
}

}  // namespace slamkit
