// The consistency figure: ANEES with its χ² band, and position and heading RMSE, over time.

#include "slamkit/report/figures.hpp"

#include <cstddef>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <mgl2/mgl.h>

#include "mgl_canvas.hpp"

namespace slamkit {
namespace {

using internal::Box;
using internal::CheckedFormat;
using internal::DrawFrame;
using internal::Escaped;
using internal::ImageFormat;
using internal::PutsAboveBox;
using internal::Range;
using internal::Region;
using internal::SuppressMglWarnings;
using internal::WriteAtomically;

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

// Layout, tuned by eye on 1200×1000 images: MathGL scales fonts with the region's size.
constexpr double kPanelLeft = -0.1;
constexpr double kPanelRight = 1.1;
constexpr double kPanelTop = 0.95;
constexpr double kPanelHeight = 0.3;
constexpr double kPanelFontSize = 6.0;

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

void WriteConsistencyFigure(const std::filesystem::path& path, const ConsistencyFigureData& data) {
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
  SuppressMglWarnings();
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
