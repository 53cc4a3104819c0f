// The figures of `slamkit coop`.
#include "cooperative/coop_figures.hpp"

#include <fmt/format.h>

#include "slamkit/report/figures.hpp"

namespace slamkit::app {
namespace {

// Run 0 under one mode: each vehicle's path (solid) over its true path (dashed), the true
// landmarks (black crosses) and each vehicle's map (circles in its colour; one map for central).
SeriesFigureData PathsFigure(const CoopModeResult& run, const LandmarkWorld& landmarks) {
  SeriesFigureData paths;
  paths.title = fmt::format("{}: paths and maps, run 0 (true paths dashed)",
                            CoopModeName(run.mode));
  paths.x_label = "x [m]";
  paths.y_label = "y [m]";
  for (std::size_t v = 0; v < run.vehicles.size(); ++v) {
    const CoopVehicleTrace& trace = run.vehicles[v];
    const int colour = static_cast<int>(v);
    Series truth{"", {}, {}, colour, true};
    Series estimate{fmt::format("vehicle {}", v), {}, {}, colour, false};
    for (const StampedPose& p : trace.truth) {
      truth.x.push_back(p.pose.x());
      truth.y.push_back(p.pose.y());
    }
    for (const StampedPose& p : trace.estimate) {
      estimate.x.push_back(p.pose.x());
      estimate.y.push_back(p.pose.y());
    }
    paths.series.push_back(std::move(truth));
    paths.series.push_back(std::move(estimate));
    if (run.mode == CoopMode::kCentral && v > 0) continue;  // every vehicle holds the same map
    Series mapped{"", {}, {}, colour, false, 'o'};
    for (const MappedLandmark& l : trace.map.landmarks) {
      mapped.x.push_back(l.position_m.x());
      mapped.y.push_back(l.position_m.y());
    }
    paths.series.push_back(std::move(mapped));
  }
  Series true_landmarks{"true landmarks", {}, {}, 5, false, '+'};
  for (const Landmark& l : landmarks.landmarks) {
    true_landmarks.x.push_back(l.position_m.x());
    true_landmarks.y.push_back(l.position_m.y());
  }
  paths.series.push_back(std::move(true_landmarks));
  return paths;
}

}  // namespace

void WriteCoopFigures(const std::filesystem::path& dir, const CoopStudyResult& r) {
  for (const CoopModeSummary& m : r.modes) {
    WriteSeriesFigure(dir / fmt::format("paths_{}.png", CoopModeName(m.mode)),
                      PathsFigure(m.first_run, r.landmarks));
  }
  SeriesFigureData cov;
  cov.title = fmt::format("Position covariance norm, mean over {} runs", r.runs);
  cov.x_label = "time [s]";
  cov.y_label = "||C_pp|| [m^2]";
  int colour = 0;
  for (const CoopModeSummary& m : r.modes) {
    if (!HasCovariance(m.mode)) continue;
    for (std::size_t v = 0; v < m.vehicles.size(); ++v) {
      cov.series.push_back({fmt::format("{} vehicle {}", CoopModeName(m.mode), v),
                            m.vehicles[v].t_s, m.vehicles[v].position_cov_norm, colour,
                            v % 2 == 1});
    }
    ++colour;
  }
  WriteSeriesFigure(dir / "covariance.png", cov);
}

}  // namespace slamkit::app
