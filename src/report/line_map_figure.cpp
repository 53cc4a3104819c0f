// The line-and-corner map figure (SPEC S1): true walls, scan points, mapped lines, corners, paths.

#include <mgl2/mgl.h>

#include <cmath>
#include <string>
#include <vector>

#include "mgl_canvas.hpp"
#include "slamkit/report/figures.hpp"

namespace slamkit {
namespace {

// Layout as the path figure's (tuned by eye on 1200×1000 images).
constexpr internal::Region kMapRegion{-0.07, 1.1, -0.05, 1.06};
constexpr double kMapFontSize = 3.0;

internal::XyData SegmentPolylines(const std::vector<Segment2>& segments) {
  internal::XyData xy;
  for (const Segment2& s : segments) {
    xy.Add(s.a.x(), s.a.y());
    xy.Add(s.b.x(), s.b.y());
    xy.Break();
  }
  return xy;
}

internal::XyData PointsOf(const std::vector<Eigen::Vector2d>& points) {
  internal::XyData xy;
  for (const Eigen::Vector2d& p : points) xy.Add(p.x(), p.y());
  return xy;
}

internal::XyData PathOf(const Trajectory& trajectory) {
  internal::XyData xy;
  for (const StampedPose& p : trajectory) xy.Add(p.pose.x(), p.pose.y());
  return xy;
}

// At most one point per output pixel of `box` (the first one that falls in it): a million scan
// points would otherwise cost MathGL seconds and look the same.
internal::XyData Decimated(const std::vector<Eigen::Vector2d>& points, const internal::Box& box,
                           int width_px, int height_px) {
  internal::XyData xy;
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
  internal::XyData walls;
  internal::XyData points;  // decimated once the view is known
  internal::XyData lines;
  internal::XyData corners;
  internal::XyData truth;
  internal::XyData estimate;
  internal::XyData odometry;
};

// The view covers walls, lines, corners and paths; scan points only where they fall inside (a
// stray far return would otherwise shrink the map).
internal::Box SetViewRanges(mglGraph& gr, const LineMapLayers& layers) {
  internal::Range rx;
  internal::Range ry;
  for (const internal::XyData* xy : {&layers.walls, &layers.lines, &layers.corners, &layers.truth,
                                     &layers.estimate, &layers.odometry}) {
    rx.Add(xy->x);
    ry.Add(xy->y);
  }
  return internal::SetEqualScaleRanges(gr, rx, ry);
}

struct LineLayer {
  const internal::XyData* xy;
  const char* pen;
  const char* legend;
};

// Bottom to top: walls, points, odometry, truth, estimate, lines, corners. False when nothing
// was drawn.
bool DrawLineMapLayers(mglGraph& gr, const LineMapLayers& layers) {
  const LineLayer drawn[] = {
      {&layers.walls, "H-1", "true walls"},        {&layers.points, "{c7} .", "scan points"},
      {&layers.odometry, "m-1", "odometry"},       {&layers.truth, "k-2", "true path"},
      {&layers.estimate, "b-2", "estimated path"}, {&layers.lines, "r-5", "mapped lines"},
      {&layers.corners, "g #o", "corners"}};
  bool any = false;
  for (const LineLayer& layer : drawn) {
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
  const internal::ImageFormat format = internal::CheckedFormat(path, data.width_px, data.height_px);
  LineMapLayers layers{SegmentPolylines(data.walls), {},
                       SegmentPolylines(data.lines), PointsOf(data.corners),
                       PathOf(data.truth),           PathOf(data.estimate),
                       PathOf(data.odometry)};
  internal::SuppressMglWarnings();
  mglGraph gr(0, data.width_px, data.height_px);
  gr.SetFontSize(kMapFontSize);
  gr.InPlot(kMapRegion.x0, kMapRegion.x1, kMapRegion.y0, kMapRegion.y1, false);
  const internal::Box box = SetViewRanges(gr, layers);
  layers.points = Decimated(data.points, box, data.width_px, data.height_px);
  internal::DrawFrame(gr, "x [m]", "y [m]");
  if (!data.title.empty())
    internal::PutsAboveBox(gr, box, internal::Escaped(data.title), 0.03, -1.4);
  if (DrawLineMapLayers(gr, layers)) {
    const internal::XyData* placed[] = {&layers.walls, &layers.points, &layers.lines,
                                        &layers.truth};
    gr.Legend(internal::EmptiestCorner(placed, box), "#", "size 2.5");
  }
  internal::WriteAtomically(gr, path, format);
}

}  // namespace slamkit
