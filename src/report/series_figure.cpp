// The series figure: several curves over one x axis with a legend (e.g. one per policy).

#include <mgl2/mgl.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "mgl_canvas.hpp"
#include "slamkit/report/figures.hpp"

namespace slamkit {
namespace {

// Layout, tuned by eye on 1200×800 images.
constexpr internal::Region kSeriesRegion{-0.06, 1.08, -0.04, 1.0};
constexpr double kSeriesFontSize = 3.0;
constexpr const char* kPalette[] = {"b", "r", "g", "m", "c", "k", "h"};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

std::string PenOf(const Series& s, int index) {
  const int colour = s.colour >= 0 ? s.colour : index;
  const std::string ink = kPalette[colour % kPaletteSize];
  if (s.marker != 0) return ink + " " + s.marker;  // a blank line style: markers only
  return ink + (s.dashed ? ";2" : "-2");
}

internal::Box SetSeriesRanges(mglGraph& gr, const SeriesFigureData& data) {
  internal::Range rx;
  internal::Range ry;
  for (const Series& s : data.series) {
    rx.Add(s.x);
    ry.Add(s.y);
  }
  const auto [x0, x1] = rx.Padded(0.0, 1e-9);
  const auto [y0, y1] = ry.Padded(0.06, 1e-9);
  const internal::Box box{mglPoint(x0, y0), mglPoint(x1, y1)};
  gr.SetRanges(box.lo, box.hi);
  return box;
}

}  // namespace

void WriteSeriesFigure(const std::filesystem::path& path, const SeriesFigureData& data) {
  const internal::ImageFormat format = internal::CheckedFormat(path, data.width_px, data.height_px);
  for (const Series& s : data.series) {
    if (s.x.size() != s.y.size()) {
      throw std::invalid_argument("series figure: series '" + s.label +
                                  "' has x and y of different lengths");
    }
  }
  internal::SuppressMglWarnings();
  mglGraph gr(0, data.width_px, data.height_px);
  gr.SetFontSize(kSeriesFontSize);
  gr.InPlot(kSeriesRegion.x0, kSeriesRegion.x1, kSeriesRegion.y0, kSeriesRegion.y1, false);
  const internal::Box box = SetSeriesRanges(gr, data);
  gr.SetTuneTicks(0);  // no common "×10³" factor: it falls off the canvas beside the x axis
  gr.SetTickTempl('x', "%g");  // 1000, not 1e3
  gr.SetTickTempl('y', "%g");
  const std::string x_label = internal::Escaped(data.x_label);
  const std::string y_label = internal::Escaped(data.y_label);
  internal::DrawFrame(gr, x_label.empty() ? nullptr : x_label.c_str(),
                      y_label.empty() ? nullptr : y_label.c_str());
  if (!data.title.empty())
    internal::PutsAboveBox(gr, box, internal::Escaped(data.title), 0.03, -1.4);
  bool any_label = false;
  for (std::size_t i = 0; i < data.series.size(); ++i) {
    const Series& s = data.series[i];
    if (s.x.empty()) continue;
    const std::string pen = PenOf(s, static_cast<int>(i));
    gr.Plot(mglData(s.x), mglData(s.y), pen.c_str());
    if (s.label.empty()) continue;
    gr.AddLegend(internal::Escaped(s.label).c_str(), pen.c_str());
    any_label = true;
  }
  if (any_label) gr.Legend(2, "#", "size 2.5");  // top left: above rising totals
  internal::WriteAtomically(gr, path, format);
}

}  // namespace slamkit
