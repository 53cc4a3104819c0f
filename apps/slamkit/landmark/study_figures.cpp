#include "landmark/study_figures.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

namespace slamkit::app {
namespace {

// The palette indexes of figures.hpp for seed 001's Fig. 3 colours, in StudyResult's order.
constexpr int kColours[] = {0, 2, 1};  // blue, green, red
constexpr int kBandColour = 5;         // black
// A diverging ANEES (FastSLAM's can reach thousands) would flatten the others against the axis:
// curves are cut at this many times the band's top, and their legend says so.
constexpr double kClipBandMultiple = 4.0;

SeriesFigureData NeesFigure(const std::string& scenario, const StudyResult& result) {
  SeriesFigureData figure;
  const ChiSquareBand& band = result.methods.front().mc.band;
  figure.title = fmt::format("{}: mean pose NEES over {} runs", scenario, result.params.runs);
  figure.x_label = "t [s]";
  figure.y_label = "ANEES (3 dof)";
  const double clip = kClipBandMultiple * band.hi;
  double last_s = 0.0;
  for (std::size_t i = 0; i < result.methods.size(); ++i) {
    const MonteCarloResult& mc = result.methods[i].mc;
    Series curve{result.methods[i].title, mc.t_s, mc.anees, kColours[i % 3], false};
    bool clipped = false;
    for (double& y : curve.y) {
      clipped = clipped || y > clip;
      y = std::min(y, clip);
    }
    if (clipped) curve.label += fmt::format(" (cut at {:.1f})", clip);
    if (!mc.t_s.empty()) last_s = std::max(last_s, mc.t_s.back());
    figure.series.push_back(std::move(curve));
  }
  const std::string label = fmt::format("95% band, {} runs", result.params.runs);
  for (const double level : {band.lo, band.hi}) {
    figure.series.push_back(
        {level == band.lo ? label : "", {0.0, last_s}, {level, level}, kBandColour, true});
  }
  return figure;
}

PathFigureData PathFigure(const std::string& scenario, const StudyMethodResult& swslam) {
  PathFigureData path;
  path.title = fmt::format("{}: {} run 0", scenario, swslam.title);
  path.truth = swslam.mc.first_run.truth;
  path.estimate = swslam.mc.first_run.estimate;
  path.true_landmarks = swslam.mc.world;
  path.map = swslam.mc.first_run.map;
  if (!swslam.traces.empty()) path.markers_m = swslam.traces.front().centres_m;
  path.markers_label = "chosen cluster centres";
  return path;
}

}  // namespace

void WriteStudyFigures(const std::filesystem::path& dir, const std::string& scenario,
                       const StudyResult& result) {
  WriteSeriesFigure(dir / "nees.png", NeesFigure(scenario, result));
  for (const StudyMethodResult& m : result.methods) {
    if (m.planner == PlannerKind::kSwslam)
      WritePathFigure(dir / "path.png", PathFigure(scenario, m));
  }
}

}  // namespace slamkit::app
