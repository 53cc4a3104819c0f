#pragma once

// A saved map as a localiser reads it: each cell's distance to the nearest occupied cell (the
// likelihood field of Thrun, Burgard and Fox, Probabilistic Robotics §6.4; AMCL's
// `likelihood_field` model) and which cells are free, from a map_server image.

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/maps/occupancy_image.hpp"

namespace slamkit {

// How the image's pixels are read: map_server's trinary convention, p = (255 - value) / 255
// (dark is occupied), occupied above occupied_threshold, free below free_threshold, unknown
// between.
struct LikelihoodFieldParams {
  double occupied_threshold = 0.65;  // map_server's default occupied_thresh
  double free_threshold = 0.196;     // map_server's default free_thresh
  double max_distance_m = 2.0;       // distances are capped here (AMCL's laser_likelihood_max_dist)
};

class LikelihoodField {
 public:
  // Throws std::invalid_argument for an empty image or a non-positive resolution.
  LikelihoodField(const OccupancyImage& image, const LikelihoodFieldParams& params = {});

  // Distance from `p` to the nearest occupied cell's centre, at most max_distance_m; points
  // outside the image are max_distance_m away.
  double DistanceM(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d c = (p - origin_m_) * inverse_resolution_;
    if (!(c.x() >= 0.0 && c.y() >= 0.0 && c.x() < width_ && c.y() < height_)) {
      return max_distance_m_;
    }
    return distance_m_[std::size_t(int(c.y())) * std::size_t(width_) + std::size_t(int(c.x()))];
  }
  bool IsFree(const Eigen::Vector2d& p) const;
  // Centres of the free cells, for a uniform draw over the free space (global localisation).
  const std::vector<Eigen::Vector2d>& FreeCells() const { return free_cells_; }
  int OccupiedCount() const { return occupied_count_; }
  double resolution() const { return resolution_m_; }

 private:
  int width_ = 0;
  int height_ = 0;  // rows, the lowest y first (the image's rows reversed)
  double resolution_m_ = 0.05;
  double inverse_resolution_ = 20.0;
  double max_distance_m_ = 2.0;
  Eigen::Vector2d origin_m_ = Eigen::Vector2d::Zero();
  std::vector<float> distance_m_;
  std::vector<std::uint8_t> free_;
  std::vector<Eigen::Vector2d> free_cells_;
  int occupied_count_ = 0;
};

// The image as an occupancy grid of `grid`'s resolution (which should be the image's): each
// pixel's cell (by its centre) at grid.log_odds_max when occupied, log_odds_min when free, unknown
// otherwise, with the thresholds of `params`. What a scan matcher reads.
OccupancyGrid OccupancyGridFromImage(const OccupancyImage& image,
                                     const LikelihoodFieldParams& params,
                                     const OccupancyGridParams& grid);

// The exact squared Euclidean distance transform of a grid (Felzenszwalb and Huttenlocher,
// Theory of Computing 2012): `f` holds 0 at the sites and a large value elsewhere, row-major,
// `width` per row; on return each entry is the squared distance in cells to the nearest site.
void SquaredDistanceTransform(std::vector<double>& f, int width, int height);

}  // namespace slamkit
