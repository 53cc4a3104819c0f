// The figures of `slamkit coop`.
#include "coop_figures.hpp"

#include <fmt/format.h>

#include "slamkit/report/figures.hpp"

namespace slamkit::app {

void WriteCoopFigures(const std::filesystem::path& dir, const CoopStudyResult& r) {
  SeriesFigureData paths;
  paths.title = fmt::format("Paths ({}, run 0): true dashed", CoopModeName(r.modes.back().mode));
  paths.x_label = "x [m]";
  paths.y_label = "y [m]";
  const CoopModeResult& last = r.modes.back().first_run;
  for (std::size_t v = 0; v < last.vehicles.size(); ++v) {
    Series truth{"", {}, {}, static_cast<int>(v), true};
    Series estimate{fmt::format("vehicle {}", v), {}, {}, static_cast<int>(v), false};
    for (const StampedPose& p : last.vehicles[v].truth) {
      truth.x.push_back(p.pose.x());
      truth.y.push_back(p.pose.y());
    }
    for (const StampedPose& p : last.vehicles[v].estimate) {
      estimate.x.push_back(p.pose.x());
      estimate.y.push_back(p.pose.y());
    }
    paths.series.push_back(std::move(truth));
    paths.series.push_back(std::move(estimate));
  }
  WriteSeriesFigure(dir / "paths.png", paths);
  SeriesFigureData cov;
  cov.title = fmt::format("Position covariance norm, mean over {} runs", r.runs);
  cov.x_label = "time [s]";
  cov.y_label = "||C_pp|| [m^2]";
  int colour = 0;
  for (const CoopModeSummary& m : r.modes) {
    if (m.mode == CoopMode::kDeadReckoning) continue;
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
