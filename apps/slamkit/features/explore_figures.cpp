#include "features/explore_figures.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace slamkit::app {
namespace {

// The band's two lines as dashed series spanning the steps drawn.
void AddBand(const ChiSquareBand& band, double last_step, int runs, SeriesFigureData* figure) {
  const std::string label = fmt::format("95% band, {} runs", runs);
  for (const double level : {band.lo, band.hi}) {
    figure->series.push_back(
        {level == band.lo ? label : "", {1.0, last_step}, {level, level}, 5, true});
  }
}

SeriesFigureData AneesFigure(const ExploreCompareResult& result) {
  SeriesFigureData figure;
  figure.title = "pose ANEES per step over the seeds";
  figure.x_label = "step";
  figure.y_label = "ANEES (3 dof)";
  double last = 1.0;
  for (const ComparePolicySummary& s : result.policies) {
    Series curve{SelectionKindName(s.policy), {}, s.anees};
    for (std::size_t k = 0; k < s.anees.size(); ++k) curve.x.push_back(double(k + 1));
    last = std::max(last, double(s.anees.size()));
    figure.series.push_back(std::move(curve));
  }
  if (!result.policies.empty()) {
    AddBand(result.policies.front().band, last, result.policies.front().runs, &figure);
  }
  return figure;
}

SeriesFigureData SlamTimeFigure(const ExploreCompareResult& result, std::uint64_t seed) {
  SeriesFigureData figure;
  figure.title = fmt::format("accumulated SLAM time, seed {}", seed);
  figure.x_label = "simulated time [s]";
  figure.y_label = "SLAM time [s]";
  for (std::size_t p = 0; p < result.policies.size(); ++p) {
    const ExplorationRun& run = result.first_seed[p].run;
    Series curve{SelectionKindName(result.policies[p].policy), {}, {}};
    double total = 0.0;
    for (std::size_t i = 0; i < run.slam_time_s.size(); ++i) {
      total += run.slam_time_s[i];
      curve.x.push_back(run.truth[i].t_s);
      curve.y.push_back(total);
    }
    figure.series.push_back(std::move(curve));
  }
  return figure;
}

}  // namespace

LineMapFigureData LineMapOf(const FloorPlan& plan, const ExploreResult& result,
                            const std::string& title) {
  LineMapFigureData figure;
  figure.title = title;
  for (const WallSegment& w : plan.walls) figure.walls.push_back({w.first, w.second});
  for (const MappedLine& l : result.lines) figure.lines.push_back({l.start_m, l.end_m});
  figure.points = result.scan_points;
  figure.corners = result.corners;
  figure.truth = result.run.truth;
  figure.estimate = result.run.estimate;
  figure.odometry = result.run.odometry;
  return figure;
}

void WriteCompareFigures(const std::filesystem::path& dir, const FloorPlan& plan,
                         const ExploreCompareResult& result, std::uint64_t first_seed) {
  WriteSeriesFigure(dir / "slam_time.png", SlamTimeFigure(result, first_seed));
  WriteSeriesFigure(dir / "nees.png", AneesFigure(result));
  for (std::size_t p = 0; p < result.policies.size(); ++p) {
    const std::string name = SelectionKindName(result.policies[p].policy);
    WriteLineMapFigure(dir / fmt::format("map_{}.png", name),
                       LineMapOf(plan, result.first_seed[p],
                                 fmt::format("explore: {} policy, seed {}", name, first_seed)));
  }
}

}  // namespace slamkit::app
