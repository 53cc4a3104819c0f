#include "slamkit/report/figures.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include <Eigen/Eigenvalues>
#include <mgl2/mgl.h>

namespace slamkit {
namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRadToDeg = 180.0 / std::numbers::pi;
constexpr int kEllipsePoints = 36;

enum class ImageFormat { kPng, kSvg };

// The format named by the extension; also rejects a canvas without pixels.
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

// MathGL reads TeX-like markup (_ ^ @ { } # \) in every string; user text must print verbatim.
std::string Escaped(std::string_view text) {
  std::string out;
  for (const char c : text) {
    if (std::string_view("\\_^@{}#").find(c) != std::string_view::npos) out += '\\';
    out += c;
  }
  return out;
}

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

// Renders `gr` into a temporary file and renames it to `path`; a failure leaves neither.
void WriteAtomically(mglGraph& gr, const fs::path& path, ImageFormat format) {
  const fs::path tmp = TemporaryPathBeside(path);
  gr.SetWarn(mglWarnNone, "");
  if (format == ImageFormat::kPng) {
    gr.WritePNG(tmp.c_str(), "", false);
  } else {
    gr.WriteSVG(tmp.c_str());
  }
  std::error_code ec;
  const bool written = gr.GetWarn() != mglWarnOpen && fs::is_regular_file(tmp, ec) &&
                       fs::file_size(tmp, ec) > 0 && !ec;
  if (written) fs::rename(tmp, path, ec);
  if (!written || ec) {
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot write figure " + path.string());
  }
}

// The span of the finite values added, widened by a margin so that nothing sits on the frame.
class Range {
 public:
  void Add(double v) {
    if (!std::isfinite(v)) return;
    lo_ = std::min(lo_, v);
    hi_ = std::max(hi_, v);
  }
  void Add(const std::vector<double>& values) {
    for (const double v : values) Add(v);
  }
  // [lo, hi] widened by `margin` of the span on each side and to at least `min_span`, or for a
  // constant series a tenth of its magnitude; [0, 1] when nothing was added.
  std::pair<double, double> Padded(double margin, double min_span) const {
    if (lo_ > hi_) return {0.0, 1.0};
    const double center = 0.5 * (lo_ + hi_);
    const double span = hi_ - lo_;
    const double floor = span > 0.0 ? min_span : std::max(min_span, 0.1 * std::abs(center));
    const double half = 0.5 * std::max(span * (1.0 + 2.0 * margin), floor);
    return {center - half, center + half};
  }

 private:
  double lo_ = std::numeric_limits<double>::infinity();
  double hi_ = -std::numeric_limits<double>::infinity();
};

// Paired coordinates for one MathGL polyline or marker set.
struct XyData {
  std::vector<double> x;
  std::vector<double> y;
  void Add(double px, double py) {
    x.push_back(px);
    y.push_back(py);
  }
  bool Empty() const { return x.empty(); }
};

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
    xy.Add(kNaN, kNaN);
  }
  return xy;
}

struct MapLayers {
  XyData truth;
  XyData estimate;
  XyData true_landmarks;
  XyData landmarks;
  XyData ellipses;
};

MapLayers BuildLayers(const PathFigureData& data) {
  MapLayers layers{PathPoints(data.truth), PathPoints(data.estimate), {}, {}, {}};
  for (const Landmark& l : data.true_landmarks.landmarks) {
    layers.true_landmarks.Add(l.position_m.x(), l.position_m.y());
  }
  for (const MappedLandmark& l : data.map.landmarks) {
    layers.landmarks.Add(l.position_m.x(), l.position_m.y());
  }
  layers.ellipses = EllipsePolylines(data.map, data.ellipse_sigma);
  return layers;
}

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

// Layout, tuned by eye on 1200×1000 images: MathGL scales fonts with the region's size.
constexpr Region kPathRegion{-0.07, 1.1, -0.05, 1.06};
constexpr double kPathFontSize = 3.0;
constexpr double kPanelLeft = -0.1;
constexpr double kPanelRight = 1.1;
constexpr double kPanelTop = 0.95;
constexpr double kPanelHeight = 0.3;
constexpr double kPanelFontSize = 6.0;

// Sets the data limits of the current region: `x` and `y` with equal scale on both axes, the
// span widened so the box is filled. Ellipses do not count: one huge fresh landmark would
// otherwise shrink the whole map.
Box SetEqualScaleRanges(mglGraph& gr, const MapLayers& layers) {
  Range rx;
  Range ry;
  for (const XyData* xy : {&layers.truth, &layers.estimate, &layers.true_landmarks,
                           &layers.landmarks}) {
    rx.Add(xy->x);
    ry.Add(xy->y);
  }
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

// The legend corner (MathGL's 0 bottom-left … 3 top-right) covering the fewest drawn points.
int EmptiestCorner(const MapLayers& layers, const Box& box) {
  std::array<int, 4> count{};
  for (const XyData* xy : {&layers.truth, &layers.estimate, &layers.true_landmarks,
                           &layers.landmarks}) {
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

struct Layer {
  const XyData* xy;
  const char* pen;
  std::string legend;
};

// Draws bottom to top (ellipses under paths under markers) and lists the legend in reading order;
// false when there was nothing to draw.
bool DrawMapLayers(mglGraph& gr, const MapLayers& layers, double sigma) {
  char ellipse_label[64];
  std::snprintf(ellipse_label, sizeof(ellipse_label), "%g\\sigma{} ellipses", sigma);
  const Layer drawn[] = {{&layers.ellipses, "{r6}-", ellipse_label},
                         {&layers.truth, "k-2", "true path"},
                         {&layers.estimate, "b-2", "estimated path"},
                         {&layers.landmarks, "r .", "estimated landmarks"},
                         {&layers.true_landmarks, "g +", "true landmarks"}};
  for (const Layer& layer : drawn) {
    if (!layer.xy->Empty()) gr.Plot(mglData(layer.xy->x), mglData(layer.xy->y), layer.pen);
  }
  bool any = false;
  for (const int i : {1, 2, 4, 3, 0}) {
    if (drawn[i].xy->Empty()) continue;
    gr.AddLegend(drawn[i].legend.c_str(), drawn[i].pen);
    any = true;
  }
  return any;
}

// Frame, grid, tick labels and axis labels for the current ranges.
void DrawFrame(mglGraph& gr, const char* x_label, const char* y_label) {
  gr.SetTickRotate(false);
  gr.Grid("xy", "{h7}");
  gr.Box();
  gr.Axis("xy");
  if (x_label != nullptr) gr.Label('x', x_label, 0);
  if (y_label != nullptr) gr.Label('y', y_label, 0, "value 0.3");  // clear of wide ticks
}

// `text` centred above the box spanning [lo, hi], `lift` box heights over its top edge (text is
// never clipped by the box, unlike lines).
void PutsAboveBox(mglGraph& gr, const Box& box, const std::string& text, double lift,
                  double size) {
  const double x = 0.5 * (box.lo.x + box.hi.x);
  const double y = box.hi.y + lift * (box.hi.y - box.lo.y);
  gr.Puts(mglPoint(x, y), text.c_str(), ":C", size);
}

void CheckSeriesLength(const std::vector<double>& series, std::size_t n, const char* name) {
  if (!series.empty() && series.size() != n) {
    throw std::invalid_argument(std::string("consistency figure: ") + name +
                                " must be empty or as long as t_s");
  }
}

struct Panel {
  const char* title;  // with the unit: a y label would collide with wide tick labels
  std::vector<double> values;
  bool has_band = false;  // dashed lines at band_lo and band_hi
  double band_lo = 0.0;
  double band_hi = 0.0;
};

// One row of the consistency figure; each panel ranges its y axis over its own data and band.
Box DrawPanel(mglGraph& gr, const Region& region, const std::vector<double>& t_s,
              const Panel& panel, bool bottom) {
  gr.InPlot(region.x0, region.x1, region.y0, region.y1, false);
  Range rt;
  rt.Add(t_s);
  Range ry;
  ry.Add(panel.values);
  if (panel.has_band) {
    ry.Add(panel.band_lo);
    ry.Add(panel.band_hi);
  }
  const auto [t0, t1] = rt.Padded(0.0, 1.0);
  const auto [y0, y1] = ry.Padded(0.08, 1e-3);
  const Box box{mglPoint(t0, y0), mglPoint(t1, y1)};
  gr.SetRanges(box.lo, box.hi);
  DrawFrame(gr, bottom ? "t [s]" : nullptr, nullptr);
  PutsAboveBox(gr, box, panel.title, 0.06, -1.3);
  if (panel.has_band) {
    gr.Line(mglPoint(t0, panel.band_lo), mglPoint(t1, panel.band_lo), "r;2");
    gr.Line(mglPoint(t0, panel.band_hi), mglPoint(t1, panel.band_hi), "r;2");
  }
  if (!panel.values.empty()) gr.Plot(mglData(t_s), mglData(panel.values), "b-2");
  return box;
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

void WritePathFigure(const fs::path& path, const PathFigureData& data) {
  const ImageFormat format = CheckedFormat(path, data.width_px, data.height_px);
  const MapLayers layers = BuildLayers(data);
  mglGraph::SuppressWarn(true);  // problems surface as exceptions, never as text on stderr
  mglGraph gr(0, data.width_px, data.height_px);
  gr.SetFontSize(kPathFontSize);
  gr.InPlot(kPathRegion.x0, kPathRegion.x1, kPathRegion.y0, kPathRegion.y1, false);
  const Box box = SetEqualScaleRanges(gr, layers);
  DrawFrame(gr, "x [m]", "y [m]");
  if (!data.title.empty()) PutsAboveBox(gr, box, Escaped(data.title), 0.03, -1.4);
  if (DrawMapLayers(gr, layers, data.ellipse_sigma)) {
    gr.Legend(EmptiestCorner(layers, box), "#", "size 2.5");
  }
  WriteAtomically(gr, path, format);
}

void WriteConsistencyFigure(const fs::path& path, const ConsistencyFigureData& data) {
  const ImageFormat format = CheckedFormat(path, data.width_px, data.height_px);
  const std::size_t n = data.t_s.size();
  CheckSeriesLength(data.anees, n, "anees");
  CheckSeriesLength(data.position_rmse_m, n, "position_rmse_m");
  CheckSeriesLength(data.heading_rmse_rad, n, "heading_rmse_rad");
  std::vector<double> heading_deg = data.heading_rmse_rad;
  for (double& v : heading_deg) v *= kRadToDeg;
  const Panel panels[] = {
      {"ANEES (95% band)", data.anees, data.band_hi > data.band_lo, data.band_lo, data.band_hi},
      {"position RMSE [m]", data.position_rmse_m},
      {"heading RMSE [deg]", heading_deg},
  };
  mglGraph::SuppressWarn(true);
  mglGraph gr(0, data.width_px, data.height_px);
  gr.SetFontSize(kPanelFontSize);
  for (int i = 0; i < 3; ++i) {
    const double top = kPanelTop - kPanelHeight * i;
    const Region region{kPanelLeft, kPanelRight, top - kPanelHeight, top};
    const Box box = DrawPanel(gr, region, data.t_s, panels[i], i == 2);
    if (i == 0 && !data.title.empty()) PutsAboveBox(gr, box, Escaped(data.title), 0.25, -1.6);
  }
  WriteAtomically(gr, path, format);
}

}  // namespace slamkit
