#include "features/feature_outputs.hpp"

#include <fmt/format.h>

#include "slamkit/io/atomic_file.hpp"
#include "slamkit/report/figures.hpp"

namespace slamkit::app {

void WriteLinesCsv(const std::filesystem::path& path, const std::vector<MappedLine>& lines) {
  WriteFileAtomically(path, [&lines](std::ostream& os) {
    os << "rho_m,alpha_rad,cov_rho_rho,cov_rho_alpha,cov_alpha_alpha,x1_m,y1_m,"
          "x2_m,y2_m\n";
    for (const MappedLine& l : lines) {
      os << fmt::format(
          "{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g},{:."
          "17g},{:.17g},{:.17g}\n",
          l.line.rho_m, l.line.alpha_rad, l.covariance(0, 0), l.covariance(0, 1),
          l.covariance(1, 1), l.start_m.x(), l.start_m.y(), l.end_m.x(), l.end_m.y());
    }
  });
}

void WriteFeatureMapFigure(const std::filesystem::path& path, const std::string& title,
                           const std::vector<MappedLine>& lines,
                           const std::vector<Eigen::Vector2d>& corners,
                           const std::vector<Eigen::Vector2d>& points,
                           const Trajectory& estimate) {
  LineMapFigureData figure;
  figure.title = title;
  for (const MappedLine& l : lines) figure.lines.push_back({l.start_m, l.end_m});
  figure.corners = corners;
  figure.points = points;
  figure.estimate = estimate;
  WriteLineMapFigure(path, figure);
}

}  // namespace slamkit::app
