// The line-and-corner map figure (SPEC S1): true walls, scan points, mapped lines, corners, paths.

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <mgl2/mgl.h>

#include "mgl_canvas.hpp"
#include "slamkit/report/figures.hpp"

namespace slamkit {
namespace {

using internal::Box;
using internal::CheckedFormat;
using internal::DrawFrame;
using internal::EmptiestCorner;
using internal::Escaped;
using internal::ImageFormat;
using internal::PutsAboveBox;
using internal::Range;
using internal::Region;
using internal::SetEqualScaleRanges;
using internal::SuppressMglWarnings;
using internal::WriteAtomically;
using internal::XyData;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Layout as the path figure's (tuned by eye on 1200×1000 images).
constexpr Region kMapRegion{-0.07, 1.1, -0.05, 1.06};
constexpr double kMapFontSize = 3.0;

XyData SegmentPolylines(const std::vector<Segment2>& segments) {
  XyData xy;
  for (const Segment2& s : segments) {
    xy.Add(s.a.x(), s.a.y());
    xy.Add(s.b.x(), s.b.y());
    xy.Add(kNaN, kNaN);
  }
  return xy;
}

XyData PointsOf(const std::vector<Eigen::Vector2d>& points) {
  XyData xy;
  for (const Eigen::Vector2d& p : points) xy.Add(p.x(), p.y());
  return xy;
}

XyData PathOf(const Trajectory& trajectory) {
  XyData xy;
  for (const StampedPose& p : trajectory) xy.Add(p.pose.x(), p.pose.y());
  return xy;
}

// At most one point per output pixel of `box` (the first one that falls in it): a million scan
// points would otherwise cost MathGL seconds and look the same.
XyData Decimated(const std::vector<Eigen::Vector2d>& points, const Box& box, int width_px,
                 int height_px) {
  XyData xy;
  std::vector<char> taken(static_cast<std::size_t>(width_px) * height_px, 0);
  const double sx = width_px / (box.hi.x - box.lo.x);
  const double sy = height_px / (box.hi.y - box.lo.y);
  for (const Eigen::Vector2d& p : points) {
    const double u = std::floor((p.x() - box.lo.x) * sx);
    const double v = std::floor((p.y() - box.lo.y) * sy);
    if (!(u >= 0.0 && u < width_px && v >= 0.0 && v < height_px)) continue;  // also NaN
    char& cell = taken[static_cast<std::size_t>(v) * width_px + static_cast<std::size_t>(u)];
    if (cell != 0) continue;
    cell = 1;
    xy.Add(p.x(), p.y());
  }
  return xy;
}

struct LineMapLayers {
  XyData walls;
  XyData points;  // decimated once the view is known
  XyData lines;
  XyData corners;
  XyData truth;
  XyData estimate;
  XyData odometry;
};

// The view covers walls, lines, corners and paths; scan points only where they fall inside (a
// stray far return would otherwise shrink the map).
Box SetViewRanges(mglGraph& gr, const LineMapLayers& layers) {
  Range rx;
  Range ry;
  for (const XyData* xy : {&layers.walls, &layers.lines, &layers.corners, &layers.truth,
                           &layers.estimate, &layers.odometry}) {
    rx.Add(xy->x);
    ry.Add(xy->y);
  }
  return SetEqualScaleRanges(gr, rx, ry);
}

struct Layer {
  const XyData* xy;
  const char* pen;
  const char* legend;
};

// Bottom to top: walls, points, odometry, truth, estimate, lines, corners. False when nothing
// was drawn.
bool DrawLineMapLayers(mglGraph& gr, const LineMapLayers& layers) {
  const Layer drawn[] = {{&layers.walls, "H-1", "true walls"},
                         {&layers.points, "{c7} .", "scan points"},
                         {&layers.odometry, "m-1", "odometry"},
                         {&layers.truth, "k-2", "true path"},
                         {&layers.estimate, "b-2", "estimated path"},
                         {&layers.lines, "r-5", "mapped lines"},
                         {&layers.corners, "g #o", "corners"}};
  bool any = false;
  for (const Layer& layer : drawn) {
    if (layer.xy->Empty()) continue;
    gr.Plot(mglData(layer.xy->x), mglData(layer.xy->y), layer.pen);
    gr.AddLegend(layer.legend, layer.pen);
    any = true;
  }
  return any;
}

}  // namespace

// SPEC S1: the map the line-and-corner EKF built, over the walls it should have found.
void WriteLineMapFigure(const std::filesystem::path& path, const LineMapFigureData& data) {
  const ImageFormat format = CheckedFormat(path, data.width_px, data.height_px);
  LineMapLayers layers{SegmentPolylines(data.walls), {}, SegmentPolylines(data.lines),
                       PointsOf(data.corners), PathOf(data.truth), PathOf(data.estimate),
                       PathOf(data.odometry)};
  SuppressMglWarnings();
  mglGraph gr(0, data.width_px, data.height_px);
  gr.SetFontSize(kMapFontSize);
  gr.InPlot(kMapRegion.x0, kMapRegion.x1, kMapRegion.y0, kMapRegion.y1, false);
  const Box box = SetViewRanges(gr, layers);
  layers.points = Decimated(data.points, box, data.width_px, data.height_px);
  DrawFrame(gr, "x [m]", "y [m]");
  if (!data.title.empty()) PutsAboveBox(gr, box, Escaped(data.title), 0.03, -1.4);
  if (DrawLineMapLayers(gr, layers)) {
    const XyData* placed[] = {&layers.walls, &layers.points, &layers.lines, &layers.truth};
    gr.Legend(EmptiestCorner(placed, box), "#", "size 2.5");
  }
  WriteAtomically(gr, path, format);
}

}  // namespace slamkit
