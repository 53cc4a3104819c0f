#include "slamkit/maps/likelihood_field.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace slamkit {

namespace {

// One row or column of the transform: the lower envelope of the parabolas rooted at each sample
// (Felzenszwalb and Huttenlocher 2012, Algorithm 1). `f` is read and written with `stride`.
void Transform1d(double* f, int n, int stride, std::vector<double>& d, std::vector<int>& v,
                 std::vector<double>& z) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  int k = 0;
  v[0] = 0;
  z[0] = -kInf;
  z[1] = kInf;
  for (int q = 1; q < n; ++q) {
    const double fq = f[q * stride];
    double s = 0.0;
    while (true) {
      const int p = v[k];
      s = ((fq + double(q) * q) - (f[p * stride] + double(p) * p)) / (2.0 * (q - p));
      if (s > z[k] || k == 0) break;
      --k;
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    const int p = v[k];
    d[q] = double(q - p) * (q - p) + f[p * stride];
  }
  for (int q = 0; q < n; ++q) f[q * stride] = d[q];
}

// map_server's trinary reading of a pixel: +1 occupied, -1 free, 0 unknown.
int PixelOccupancy(std::uint8_t value, const LikelihoodFieldParams& params) {
  const double p = (255.0 - value) / 255.0;
  if (p > params.occupied_threshold) return 1;
  return p < params.free_threshold ? -1 : 0;
}

}  // namespace

void SquaredDistanceTransform(std::vector<double>& f, int width, int height) {
  const int n = std::max(width, height);
  std::vector<double> d(n);
  std::vector<int> v(n);
  std::vector<double> z(n + 1);
  for (int x = 0; x < width; ++x) Transform1d(f.data() + x, height, width, d, v, z);
  for (int y = 0; y < height; ++y) {
    Transform1d(f.data() + std::size_t(y) * width, width, 1, d, v, z);
  }
}

LikelihoodField::LikelihoodField(const OccupancyImage& image, const LikelihoodFieldParams& params)
    : width_(image.width),
      height_(image.height),
      resolution_m_(image.resolution_m),
      inverse_resolution_(1.0 / image.resolution_m),
      max_distance_m_(params.max_distance_m),
      origin_m_(image.origin_m) {
  if (width_ <= 0 || height_ <= 0 || image.pixels.size() != std::size_t(width_) * height_) {
    throw std::invalid_argument("LikelihoodField: the map image is empty or its size is wrong");
  }
  if (!(resolution_m_ > 0.0) || !(max_distance_m_ > 0.0)) {
    throw std::invalid_argument("LikelihoodField: resolution and max distance must be > 0");
  }
  const std::size_t cells = std::size_t(width_) * height_;
  // Sites at 0; elsewhere a value beyond any distance the cap keeps, yet finite for the envelope.
  const double far = std::pow(max_distance_m_ * inverse_resolution_ + 2.0, 2) + 1.0;
  std::vector<double> f(cells, far);
  free_.assign(cells, 0);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      // Image rows run from the top (largest y) down.
      const int occupancy =
          PixelOccupancy(image.pixels[std::size_t(height_ - 1 - y) * width_ + x], params);
      const std::size_t i = std::size_t(y) * width_ + x;
      if (occupancy > 0) {
        f[i] = 0.0;
        ++occupied_count_;
      } else if (occupancy < 0) {
        free_[i] = 1;
        free_cells_.push_back(origin_m_ + resolution_m_ * Eigen::Vector2d(x + 0.5, y + 0.5));
      }
    }
  }
  SquaredDistanceTransform(f, width_, height_);
  distance_m_.resize(cells);
  for (std::size_t i = 0; i < cells; ++i) {
    distance_m_[i] = float(std::min(std::sqrt(f[i]) * resolution_m_, max_distance_m_));
  }
}

OccupancyGrid OccupancyGridFromImage(const OccupancyImage& image,
                                     const LikelihoodFieldParams& params,
                                     const OccupancyGridParams& grid_params) {
  OccupancyGrid grid(grid_params);
  const long occupied = OccupancyGrid::ToSteps(grid_params.log_odds_max);
  const long free = OccupancyGrid::ToSteps(grid_params.log_odds_min);
  for (int row = 0; row < image.height; ++row) {
    for (int x = 0; x < image.width; ++x) {
      const int occupancy =
          PixelOccupancy(image.pixels[std::size_t(row) * image.width + x], params);
      if (occupancy == 0) continue;
      const int y = image.height - 1 - row;
      const Eigen::Vector2d centre =
          image.origin_m + image.resolution_m * Eigen::Vector2d(x + 0.5, y + 0.5);
      grid.UpdateSteps(grid.WorldToCell(centre), occupancy > 0 ? occupied : free);
    }
  }
  return grid;
}

bool LikelihoodField::IsFree(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d c = (p - origin_m_) * inverse_resolution_;
  if (!(c.x() >= 0.0 && c.y() >= 0.0 && c.x() < width_ && c.y() < height_)) return false;
  return free_[std::size_t(int(c.y())) * std::size_t(width_) + std::size_t(int(c.x()))] != 0;
}

}  // namespace slamkit
