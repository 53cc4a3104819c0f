#include "slamkit/eval/map_alignment.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace slamkit {
namespace {

constexpr std::uint8_t kUnknownPixel = 205;

bool Occupied(std::uint8_t v, double threshold) { return (255.0 - v) / 255.0 > threshold; }

// The centre of pixel (col, row-from-top).
Eigen::Vector2d PixelCentre(const OccupancyImage& m, int col, int row) {
  return m.origin_m + m.resolution_m * Eigen::Vector2d(col + 0.5, m.height - row - 0.5);
}

// Chessboard distance in pixels from each pixel of `m` to its nearest wall (two passes), capped.
std::vector<std::uint8_t> WallDistance(const OccupancyImage& m, double threshold) {
  const int w = m.width, h = m.height;
  std::vector<std::uint8_t> d(m.pixels.size(), 255);
  auto at = [&](int c, int r) -> std::uint8_t& { return d[std::size_t(r) * w + c]; };
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      if (Occupied(m.pixels[std::size_t(r) * w + c], threshold)) at(c, r) = 0;
    }
  }
  auto relax = [&](int c, int r, int dc, int dr) {
    const int cc = c + dc, rr = r + dr;
    if (cc < 0 || rr < 0 || cc >= w || rr >= h) return;
    at(c, r) = std::min<int>(at(c, r), std::min(254, at(cc, rr) + 1));
  };
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      relax(c, r, -1, 0), relax(c, r, -1, -1), relax(c, r, 0, -1), relax(c, r, 1, -1);
    }
  }
  for (int r = h - 1; r >= 0; --r) {
    for (int c = w - 1; c >= 0; --c) {
      relax(c, r, 1, 0), relax(c, r, 1, 1), relax(c, r, 0, 1), relax(c, r, -1, 1);
    }
  }
  return d;
}

struct Scorer {
  const OccupancyImage& first;
  std::vector<std::uint8_t> distance;
  std::vector<Eigen::Vector2d> points;  // the second map's wall cells

  // A wall cell of the second map landing d pixels from a wall of the first counts
  // 1 − d / (reach + 1): smooth enough for a search in steps of `reach` cells.
  double Score(const Pose2& t, int reach, int stride) const {
    double sum = 0.0;
    int n = 0;
    for (std::size_t i = 0; i < points.size(); i += stride, ++n) {
      const Eigen::Vector2d q =
          (t.TransformFrom(points[i]) - first.origin_m) / first.resolution_m;
      const int col = static_cast<int>(std::floor(q.x()));
      const int row = first.height - 1 - static_cast<int>(std::floor(q.y()));
      if (col < 0 || row < 0 || col >= first.width || row >= first.height) continue;
      const int d = distance[std::size_t(row) * first.width + col];
      if (d <= reach) sum += 1.0 - double(d) / (reach + 1);
    }
    return n == 0 ? 0.0 : sum / n;
  }
};

std::vector<Eigen::Vector2d> WallPoints(const OccupancyImage& m, const MapAlignmentParams& p) {
  std::vector<Eigen::Vector2d> all;
  for (int row = 0; row < m.height; ++row) {
    for (int col = 0; col < m.width; ++col) {
      if (Occupied(m.pixels[std::size_t(row) * m.width + col], p.occupied_threshold)) {
        all.push_back(PixelCentre(m, col, row));
      }
    }
  }
  if (static_cast<int>(all.size()) <= p.max_points) return all;
  std::vector<Eigen::Vector2d> kept;
  const double stride = double(all.size()) / p.max_points;
  for (int i = 0; i < p.max_points; ++i) kept.push_back(all[std::size_t(i * stride)]);
  return kept;
}

struct Level {
  double shift_m, rotation_rad, step_m, step_rad;
  int reach, stride;
};

// The best pose on a grid of steps around `centre` (ties: the first, in loop order).
MapAlignment Search(const Scorer& s, const Pose2& centre, const Level& l) {
  MapAlignment best{centre, s.Score(centre, l.reach, l.stride)};
  const int nt = static_cast<int>(std::floor(l.shift_m / l.step_m + 1e-9));  // within bounds
  const int nr = static_cast<int>(std::floor(l.rotation_rad / l.step_rad + 1e-9));
  for (int k = -nr; k <= nr; ++k) {
    for (int i = -nt; i <= nt; ++i) {
      for (int j = -nt; j <= nt; ++j) {
        const Pose2 t(centre.x() + i * l.step_m, centre.y() + j * l.step_m,
                      centre.theta() + k * l.step_rad);
        const double score = s.Score(t, l.reach, l.stride);
        if (score > best.score) best = {t, score};
      }
    }
  }
  return best;
}

}  // namespace

MapAlignment AlignMaps(const OccupancyImage& first, const OccupancyImage& second,
                       const MapAlignmentParams& params) {
  const double res = first.resolution_m;
  if (!(res > 0.0) || std::abs(res - second.resolution_m) > 1e-9 * res ||
      !(params.max_shift_m >= 0.0) || !(params.max_rotation_rad >= 0.0) || params.max_points < 1) {
    throw std::invalid_argument(
        "map alignment: the maps' resolutions differ, or a bound is negative");
  }
  const Scorer scorer{first, WallDistance(first, params.occupied_threshold),
                      WallPoints(second, params)};
  double extent = res;
  for (const Eigen::Vector2d& p : scorer.points) {
    extent = std::max(extent, (p - scorer.points.front()).norm());
  }
  const double step_rad = std::max(res / extent, 1e-5);  // a cell's turn at the far end
  // Coarse to fine: steps of 4 cells on every 2nd wall cell, then 1 cell, then a quarter.
  const std::vector<Level> levels = {
      {params.max_shift_m, params.max_rotation_rad, 4 * res, 4 * step_rad, 4, 2},
      {4 * res, 4 * step_rad, res, step_rad, 1, 1},
      {res, step_rad, 0.25 * res, 0.25 * step_rad, 1, 1}};
  // The finer levels search around the coarse result: they may step past the bounds by a cell.
  MapAlignment best{Pose2(), 0.0};
  for (const Level& level : levels) best = Search(scorer, best.transform, level);
  best.score = scorer.Score(best.transform, 1, 1);
  return best;
}

OccupancyImage ResampleMap(const OccupancyImage& first, const OccupancyImage& second,
                           const Pose2& transform) {
  OccupancyImage out = first;
  const Pose2 back = transform.Inverse();
  for (int row = 0; row < first.height; ++row) {
    for (int col = 0; col < first.width; ++col) {
      const Eigen::Vector2d q =
          (back.TransformFrom(PixelCentre(first, col, row)) - second.origin_m) /
          second.resolution_m;
      const int c = static_cast<int>(std::floor(q.x()));
      const int r = second.height - 1 - static_cast<int>(std::floor(q.y()));
      const bool inside = c >= 0 && r >= 0 && c < second.width && r < second.height;
      out.pixels[std::size_t(row) * first.width + col] =
          inside ? second.pixels[std::size_t(r) * second.width + c] : kUnknownPixel;
    }
  }
  return out;
}

}  // namespace slamkit
