// The map figure: true and estimated paths, landmarks and their covariance ellipses.

#include "slamkit/report/figures.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <mgl2/mgl.h>

#include "mgl_canvas.hpp"

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

constexpr int kEllipsePoints = 36;
constexpr double kMarkerSize = 1.5;  // of PathFigureData::markers_m, MathGL's default being 1

// Layout, tuned by eye on 1200×1000 images: MathGL scales fonts with the region's size.
constexpr Region kPathRegion{-0.07, 1.1, -0.05, 1.06};
constexpr double kPathFontSize = 3.0;

XyData PathPoints(const Trajectory& trajectory) {
  XyData xy;
  for (const StampedPose& p : trajectory) xy.Add(p.pose.x(), p.pose.y());
  return xy;
}

// Every ellipse as a closed polyline followed by a NaN, where MathGL breaks the line.
XyData EllipsePolylines(const LandmarkMap& map, double sigma) {
  XyData xy;
  xy.x.reserve(map.landmarks.size() * (kEllipsePoints + 2));
  xy.y.reserve(xy.x.capacity());
  for (const MappedLandmark& l : map.landmarks) {
    const std::vector<Eigen::Vector2d> ring =
        CovarianceEllipse(l.position_m, l.covariance, sigma, kEllipsePoints);
    for (const Eigen::Vector2d& p : ring) xy.Add(p.x(), p.y());
    xy.Add(ring.front().x(), ring.front().y());
    xy.Break();
  }
  return xy;
}

struct MapLayers {
  XyData truth;
  XyData estimate;
  XyData true_landmarks;
  XyData landmarks;
  XyData ellipses;
  XyData markers;
};

// The layers that place the view and the legend: all but the ellipses.
std::array<const XyData*, 5> MarkedLayers(const MapLayers& layers) {
  return {&layers.truth, &layers.estimate, &layers.true_landmarks, &layers.landmarks,
          &layers.markers};
}

MapLayers BuildLayers(const PathFigureData& data) {
  MapLayers layers{PathPoints(data.truth), PathPoints(data.estimate), {}, {}, {}, {}};
  for (const Eigen::Vector2d& p : data.markers_m) layers.markers.Add(p.x(), p.y());
  for (const Landmark& l : data.true_landmarks.landmarks) {
    layers.true_landmarks.Add(l.position_m.x(), l.position_m.y());
  }
  for (const MappedLandmark& l : data.map.landmarks) {
    layers.landmarks.Add(l.position_m.x(), l.position_m.y());
  }
  layers.ellipses = EllipsePolylines(data.map, data.ellipse_sigma);
  return layers;
}

// Equal scale on both axes over paths and landmarks. Ellipses do not count: one huge fresh
// landmark would otherwise shrink the whole map.
Box SetMapRanges(mglGraph& gr, const MapLayers& layers) {
  Range rx;
  Range ry;
  for (const XyData* xy : MarkedLayers(layers)) {
    rx.Add(xy->x);
    ry.Add(xy->y);
  }
  return SetEqualScaleRanges(gr, rx, ry);
}

struct PathLayer {
  const XyData* xy;
  const char* pen;
  std::string legend;
};

// Draws bottom to top (ellipses under paths under markers) and lists the legend in reading order;
// false when there was nothing to draw.
bool DrawMapLayers(mglGraph& gr, const MapLayers& layers, const PathFigureData& data) {
  const double sigma = data.ellipse_sigma;
  char ellipse_label[64];
  std::snprintf(ellipse_label, sizeof(ellipse_label), "%g\\sigma{} ellipses", sigma);
  const PathLayer drawn[] = {{&layers.ellipses, "{r6}-", ellipse_label},
                             {&layers.truth, "k-2", "true path"},
                             {&layers.estimate, "b-2", "estimated path"},
                             {&layers.landmarks, "r .", "estimated landmarks"},
                             {&layers.true_landmarks, "g +", "true landmarks"},
                             {&layers.markers, "m #o", Escaped(data.markers_label)}};
  for (const PathLayer& layer : drawn) {
    if (layer.xy->Empty()) continue;
    // The few marked points must stand out among the landmarks: larger circles.
    if (layer.xy == &layers.markers) gr.SetMarkSize(kMarkerSize);
    gr.Plot(mglData(layer.xy->x), mglData(layer.xy->y), layer.pen);
    if (layer.xy == &layers.markers) gr.SetMarkSize(1.0);
  }
  bool any = false;
  for (const int i : {1, 2, 4, 3, 5, 0}) {
    if (drawn[i].xy->Empty()) continue;
    gr.AddLegend(drawn[i].legend.c_str(), drawn[i].pen);
    any = true;
  }
  return any;
}

}  // namespace

std::vector<Eigen::Vector2d> CovarianceEllipse(const Eigen::Vector2d& mean,
                                               const Eigen::Matrix2d& cov, double sigma,
                                               int points) {
  // cov = V Λ Vᵀ, so L = V Λ^½ satisfies L Lᵀ = cov; eigenvalues come in increasing order, and
  // the columns are swapped so that u = (1, 0) maps to the major semi-axis.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(cov);
  const Eigen::Vector2d root = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  Eigen::Matrix2d L;
  L.col(0) = eigen.eigenvectors().col(1) * root(1);
  L.col(1) = eigen.eigenvectors().col(0) * root(0);
  std::vector<Eigen::Vector2d> ring;
  ring.reserve(static_cast<std::size_t>(std::max(points, 0)));
  for (int k = 0; k < points; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / points;
    ring.push_back(mean + sigma * (L * Eigen::Vector2d(std::cos(angle), std::sin(angle))));
  }
  return ring;
}

void WritePathFigure(const std::filesystem::path& path, const PathFigureData& data) {
  const ImageFormat format = CheckedFormat(path, data.width_px, data.height_px);
  const MapLayers layers = BuildLayers(data);
  SuppressMglWarnings();
  mglGraph gr(0, data.width_px, data.height_px);
  gr.SetFontSize(kPathFontSize);
  gr.InPlot(kPathRegion.x0, kPathRegion.x1, kPathRegion.y0, kPathRegion.y1, false);
  const Box box = SetMapRanges(gr, layers);
  DrawFrame(gr, "x [m]", "y [m]");
  if (!data.title.empty()) PutsAboveBox(gr, box, Escaped(data.title), 0.03, -1.4);
  if (DrawMapLayers(gr, layers, data)) {
    gr.Legend(EmptiestCorner(MarkedLayers(layers), box), "#", "size 2.5");
  }
  WriteAtomically(gr, path, format);
}

}  // namespace slamkit
