#include "slamkit/features/grid_structure.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

constexpr double kPi = std::numbers::pi;

// An occupied cell of the disc.
struct Cell {
  Eigen::Vector2d p;   // centre, world frame [m]
  bool taken = false;  // gathered by an earlier peak: its votes are withdrawn
};

// An infinite line through `point` along the unit vector `dir`.
struct Line2 {
  Eigen::Vector2d point;
  Eigen::Vector2d dir;
  double Along(const Eigen::Vector2d& p) const { return (p - point).dot(dir); }
  double Distance(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d d = p - point;
    return std::abs(d.x() * dir.y() - d.y() * dir.x());
  }
};

// In (−π, π]: WrapAngle gives [−π, π).
double WrapUpper(double angle_rad) { return -WrapAngle(-angle_rad); }

void Validate(const GridStructureParams& p) {
  auto check = [](double v, const char* name) {
    if (!(v > 0.0)) {
      throw std::invalid_argument(std::string("GridStructureParams: ") + name +
                                  " must be > 0, not " + std::to_string(v));
    }
  };
  check(p.angle_step_rad, "angle_step_rad");
  check(p.min_segment_length_m, "min_segment_length_m");
  check(p.line_tolerance_m, "line_tolerance_m");
}

// SPEC S4, step 2: the occupied cells whose centres lie in the disc. Only the disc's bounding box,
// clipped to the written cells, is visited, and a cell is tested against the disc before it is
// read. The box is clipped in double before any cast, so a far centre cannot overflow an int.
std::vector<Cell> CollectOccupiedCells(const OccupancyGrid& grid, const Eigen::Vector2d& center_m,
                                       double radius_m, double occupied_probability) {
  std::vector<Cell> cells;
  const CellIndex lo = grid.min_cell(), hi = grid.max_cell();
  if (lo.x > hi.x || !center_m.allFinite() || !(radius_m >= 0.0)) return cells;
  const double res = grid.resolution();
  const double x0 = std::floor((center_m.x() - radius_m) / res);
  const double x1 = std::floor((center_m.x() + radius_m) / res);
  const double y0 = std::floor((center_m.y() - radius_m) / res);
  const double y1 = std::floor((center_m.y() + radius_m) / res);
  if (x1 < lo.x || x0 > hi.x || y1 < lo.y || y0 > hi.y) return cells;
  const int bx0 = static_cast<int>(std::max<double>(x0, lo.x));
  const int bx1 = static_cast<int>(std::min<double>(x1, hi.x));
  const int by0 = static_cast<int>(std::max<double>(y0, lo.y));
  const int by1 = static_cast<int>(std::min<double>(y1, hi.y));
  const double r2 = radius_m * radius_m;
  for (int y = by0; y <= by1; ++y) {
    for (int x = bx0; x <= bx1; ++x) {
      const CellIndex c{x, y};
      const Eigen::Vector2d centre = grid.CellCenter(c);
      if ((centre - center_m).squaredNorm() > r2) continue;
      if (grid.Probability(c) > occupied_probability) cells.push_back({centre});
    }
  }
  return cells;
}

// SPEC S4, step 3 (Hough transform): votes over normals θ_k = k·π/n, k < n, × ρ in whole cells,
// measured from the centre of the cells' bounding box so that the ρ range is as small as they are.
class HoughAccumulator {
 public:
  struct Peak {
    int votes = 0;
    int theta = 0;  // index k
    int rho = 0;    // bin
  };

  HoughAccumulator(const std::vector<Cell>& cells, double resolution_m, double angle_step_rad)
      : resolution_m_(resolution_m) {
    Eigen::Vector2d lo = cells.front().p, hi = lo;
    for (const Cell& c : cells) {
      lo = lo.cwiseMin(c.p);
      hi = hi.cwiseMax(c.p);
    }
    origin_ = 0.5 * (lo + hi);
    rho_offset_ = static_cast<int>(std::ceil(0.5 * (hi - lo).norm() / resolution_m)) + 1;
    n_rho_ = 2 * rho_offset_ + 1;
    const int n_theta = std::max(1, static_cast<int>(std::lround(kPi / angle_step_rad)));
    for (int k = 0; k < n_theta; ++k) {
      normals_.emplace_back(std::cos(k * kPi / n_theta), std::sin(k * kPi / n_theta));
    }
    votes_.assign(std::size_t(n_theta) * std::size_t(n_rho_), 0);
    for (const Cell& c : cells) Vote(c.p, +1);
  }

  int Bin(const Eigen::Vector2d& p, int theta) const {
    return static_cast<int>(std::lround((p - origin_).dot(normals_[theta]) / resolution_m_)) +
           rho_offset_;
  }
  void Vote(const Eigen::Vector2d& p, int delta) {
    for (int k = 0; k < static_cast<int>(normals_.size()); ++k) {
      votes_[std::size_t(k) * std::size_t(n_rho_) + std::size_t(Bin(p, k))] += delta;
    }
  }
  // Ties go to the lowest (θ, ρ) index, so the order of extraction is reproducible.
  Peak Strongest() const {
    const auto it = std::max_element(votes_.begin(), votes_.end());
    const int i = static_cast<int>(it - votes_.begin());
    return {*it, i / n_rho_, i % n_rho_};
  }
  // The peak's line: its points p have n·(p − origin) = (bin − offset)·resolution.
  Line2 LineOf(const Peak& peak) const {
    const Eigen::Vector2d& n = normals_[peak.theta];
    return {origin_ + (peak.rho - rho_offset_) * resolution_m_ * n, Eigen::Vector2d(-n.y(), n.x())};
  }

 private:
  double resolution_m_;
  Eigen::Vector2d origin_;
  int rho_offset_ = 0;
  int n_rho_ = 0;
  std::vector<Eigen::Vector2d> normals_;
  std::vector<int> votes_;
};

// Total least squares: the principal axis of the cells' centres, its direction in (−π/2, π/2]
// (the closed form gives exactly 0 or π/2 for an axis-aligned wall).
Line2 FitAxis(const std::vector<Cell>& cells, const std::vector<int>& members) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (int i : members) mean += cells[i].p;
  mean /= static_cast<double>(members.size());
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  for (int i : members) {
    const Eigen::Vector2d d = cells[i].p - mean;
    sxx += d.x() * d.x();
    syy += d.y() * d.y();
    sxy += d.x() * d.y();
  }
  double a = 0.5 * std::atan2(2.0 * sxy, sxx - syy);
  if (a <= -0.5 * kPi + 1e-12) a += kPi;  // a sum of −0.0 can give −π/2 for a vertical wall
  return {mean, Eigen::Vector2d(std::cos(a), std::sin(a))};
}

// The segment of one run: its own fit, its extreme cells projected onto it.
GridLine MakeLine(const std::vector<Cell>& cells, const std::vector<int>& run) {
  const Line2 axis = FitAxis(cells, run);
  double t0 = axis.Along(cells[run.front()].p), t1 = t0;
  for (int i : run) {
    t0 = std::min(t0, axis.Along(cells[i].p));
    t1 = std::max(t1, axis.Along(cells[i].p));
  }
  GridLine line;
  line.start_m = axis.point + t0 * axis.dir;
  line.end_m = axis.point + t1 * axis.dir;
  line.angle_rad = std::atan2(axis.dir.y(), axis.dir.x());
  line.cells = static_cast<int>(run.size());
  return line;
}

// Splits `members`, sorted along `line`, into runs at gaps wider than max_gap_m; appends the runs
// long enough, and holding at least `min_fresh` cells of their own (cells of an earlier line, as a
// corner's, are shared but are no evidence), to *out.
void AppendRuns(const std::vector<Cell>& cells, const Line2& line, const std::vector<int>& members,
                const GridStructureParams& params, int min_fresh, std::vector<GridLine>* out) {
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= members.size(); ++i) {
    if (i < members.size() && line.Along(cells[members[i]].p) -
                                      line.Along(cells[members[i - 1]].p) <= params.max_gap_m) {
      continue;
    }
    const std::vector<int> run(members.begin() + long(begin), members.begin() + long(i));
    begin = i;
    const auto fresh = std::count_if(run.begin(), run.end(), [&](int k) { return !cells[k].taken; });
    if (fresh < min_fresh || run.size() < 2) continue;
    GridLine segment = MakeLine(cells, run);
    if (segment.LengthM() >= params.min_segment_length_m) out->push_back(segment);
  }
}

// The cells within `tolerance_m` of `line`, in index order.
std::vector<int> Gather(const std::vector<Cell>& cells, const Line2& line, double tolerance_m) {
  std::vector<int> members;
  for (int i = 0; i < static_cast<int>(cells.size()); ++i) {
    if (line.Distance(cells[i].p) <= tolerance_m) members.push_back(i);
  }
  return members;
}

// Refits passes after the first: each re-centres the band on the wall (a peak can sit on one
// edge of a two-cell-wide wall, or on one row of a wall a degree off an axis).
constexpr int kRefits = 3;

// SPEC S4, step 3: the segments of one Hough peak. The peak's line is only as good as its θ and ρ
// bins (half a degree over a 10 m wall is almost a cell), so the cells within a band one cell
// wider than line_tolerance_m are fitted, and the fit is refined on the cells within
// line_tolerance_m of it. The final band's cells and the peak's own bin are then taken and
// un-voted: each peak removes at least its votes, so the extraction ends.
void TakePeak(const HoughAccumulator::Peak& peak, std::vector<Cell>& cells,
              HoughAccumulator& hough, const GridStructureParams& params, double resolution_m,
              int min_fresh, std::vector<GridLine>* out) {
  std::vector<int> near = Gather(cells, hough.LineOf(peak), params.line_tolerance_m + resolution_m);
  Line2 fit = FitAxis(cells, near);
  for (int pass = 0; pass < kRefits; ++pass) {
    std::vector<int> band = Gather(cells, fit, params.line_tolerance_m);
    if (band.size() < 2 || band == near) break;
    near = std::move(band);
    fit = FitAxis(cells, near);
  }
  near = Gather(cells, fit, params.line_tolerance_m);
  std::vector<int> sorted = near;
  std::stable_sort(sorted.begin(), sorted.end(), [&](int a, int b) {
    return fit.Along(cells[a].p) < fit.Along(cells[b].p);
  });
  AppendRuns(cells, fit, sorted, params, min_fresh, out);
  for (int i = 0; i < static_cast<int>(cells.size()); ++i) {
    const bool in_bin = hough.Bin(cells[i].p, peak.theta) == peak.rho;
    if (cells[i].taken || (!in_bin && !std::binary_search(near.begin(), near.end(), i))) continue;
    hough.Vote(cells[i].p, -1);
    cells[i].taken = true;
  }
}

// Arm of `line` at corner `p`: along the line toward its end farther from p.
double ArmAngle(const GridLine& line, const Eigen::Vector2d& p) {
  return (line.end_m - p).norm() >= (line.start_m - p).norm() ? line.angle_rad
                                                               : WrapUpper(line.angle_rad + kPi);
}

double NearerEndDistance(const GridLine& line, const Eigen::Vector2d& p) {
  return std::min((line.start_m - p).norm(), (line.end_m - p).norm());
}

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// SPEC S4, step 3: the L-corner of `a` and `b`, if they make one.
bool MakeCorner(const GridLine& a, const GridLine& b, const GridStructureParams& params,
                GridCorner* corner) {
  // Undirected angle between the lines, in [0, π/2]; never let parallel lines through.
  const double between = std::abs(std::remainder(a.angle_rad - b.angle_rad, kPi));
  if (between < std::max(params.min_corner_angle_rad, 1e-6)) return false;
  const Eigen::Vector2d ua(std::cos(a.angle_rad), std::sin(a.angle_rad));
  const Eigen::Vector2d ub(std::cos(b.angle_rad), std::sin(b.angle_rad));
  const double t = Cross(b.start_m - a.start_m, ub) / Cross(ua, ub);
  const Eigen::Vector2d p = a.start_m + t * ua;
  if (NearerEndDistance(a, p) > params.corner_max_gap_m ||
      NearerEndDistance(b, p) > params.corner_max_gap_m) {
    return false;
  }
  corner->position_m = p;
  corner->line_angles_rad = {ArmAngle(a, p), ArmAngle(b, p)};
  return true;
}

}  // namespace

// SPEC S4, step 3 (P-SLAM seed III-A 1: "line features are extracted from Hough transform").
std::vector<GridLine> ExtractGridLines(const OccupancyGrid& grid, const Eigen::Vector2d& center_m,
                                       double radius_m, const GridStructureParams& params) {
  Validate(params);
  std::vector<Cell> cells =
      CollectOccupiedCells(grid, center_m, radius_m, params.occupied_probability);
  std::vector<GridLine> lines;
  if (cells.empty() || params.max_lines <= 0) return lines;
  const double res = grid.resolution();
  // The fewest cells a digital line of the minimum length has (at 45°).
  const int min_votes = std::max(
      2, static_cast<int>(std::floor(params.min_segment_length_m / (std::sqrt(2.0) * res))));
  HoughAccumulator hough(cells, res, params.angle_step_rad);
  while (static_cast<int>(lines.size()) < params.max_lines) {
    const HoughAccumulator::Peak peak = hough.Strongest();
    if (peak.votes < min_votes) break;
    TakePeak(peak, cells, hough, params, res, min_votes, &lines);
  }
  if (static_cast<int>(lines.size()) > params.max_lines) lines.resize(params.max_lines);
  return lines;
}

// SPEC S4, step 3 (corners as line intersections; the seed's image gradients would find the same
// points but not the two line angles each control point needs for Eq. 2).
std::vector<GridCorner> ExtractGridCorners(const std::vector<GridLine>& lines,
                                           const GridStructureParams& params) {
  std::vector<GridCorner> corners;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    for (std::size_t j = i + 1; j < lines.size(); ++j) {
      GridCorner c;
      if (!MakeCorner(lines[i], lines[j], params, &c)) continue;
      const bool duplicate = std::any_of(corners.begin(), corners.end(), [&](const GridCorner& o) {
        return (o.position_m - c.position_m).norm() < params.corner_max_gap_m;
      });
      if (!duplicate) corners.push_back(c);
    }
  }
  return corners;
}

}  // namespace slamkit
