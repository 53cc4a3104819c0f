#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

// Correlative scan matching of a scan against a finished map over a search window, exhaustively
// or by branch and bound over precomputed max-filtered grids (Olson 2009; Hess, Kohler, Rapp and
// Andor, "Real-time loop closure in 2D LIDAR SLAM", ICRA 2016, Section V): the loop-closure
// search of a graph back end.
struct CorrelativeMatcherParams {
  double linear_window_m = 3.0;     // ± this in x and in y around the initial pose
  double angular_window_rad = 0.35; // ± this in θ
  // The angular step; 0: from the scan's farthest point d_max, δθ = acos(1 − r² / (2 d_max²))
  // with r the map's resolution (Hess et al. Eq. 7), so no point moves by more than a cell.
  double angular_step_rad = 0.0;
  int branch_and_bound_depth = 7;   // precomputed grids; the coarsest is 2^(depth−1) cells wide
  double min_score = 0.55;          // a match scoring less is no match
};

// A search window around the initial pose: ± linear_m in x and in y, ± angular_rad in θ.
struct CorrelativeWindow {
  double linear_m = 3.0;
  double angular_rad = 0.35;
};

struct CorrelativeMatch {
  Pose2 pose;          // the scan's pose in the map frame
  double score = 0.0;  // the mean over the points of the map's occupancy at their cells
};

// The map is read once, on construction: its known cells' occupancy probabilities, unknown
// cells scoring 0 (a point in unexplored space supports nothing).
class CorrelativeMatcher {
 public:
  // Throws std::invalid_argument for windows or depth that are not positive or a min_score
  // outside [0, 1].
  CorrelativeMatcher(const OccupancyGrid& map, const CorrelativeMatcherParams& params = {});

  // The best pose over the window around `initial` (points in the scan's frame, metres), if it
  // scores at least min_score; the window is the params' unless given. Exhaustive tries every
  // candidate; BranchAndBound gives the same best score (ties aside, the same pose) visiting far
  // fewer. With `scored`, the candidates scored at any level (for benchmarks). Both are safe to
  // call from several threads at once.
  std::optional<CorrelativeMatch> Exhaustive(const std::vector<Eigen::Vector2d>& points,
                                             const Pose2& initial,
                                             const std::optional<CorrelativeWindow>& window = {},
                                             long* scored = nullptr) const;
  std::optional<CorrelativeMatch> BranchAndBound(
      const std::vector<Eigen::Vector2d>& points, const Pose2& initial,
      const std::optional<CorrelativeWindow>& window = {}, long* scored = nullptr) const;

 private:
  // One level: each cell the max of the 2^level × 2^level cells from it, as a probability in
  // steps of 1/kProbabilitySteps (16 bits rather than a float: the levels are the largest thing
  // a graph run holds while it searches, one set per submap searched at once).
  static constexpr int kProbabilitySteps = 65535;
  struct Grid {
    std::vector<std::uint16_t> value;
  };
  struct Rotated {  // the points turned by one angle, as cell offsets from the initial pose
    double theta = 0.0;
    std::vector<Eigen::Vector2i> cells;
  };
  struct Candidate {
    int rotation = 0, dx = 0, dy = 0, level = 0;
    double score = 0.0;
  };
  struct Query {  // one call's scan, window and count
    std::vector<Rotated> rotations;
    int window_cells = 0;
    long scored = 0;
  };
  Query MakeQuery(const std::vector<Eigen::Vector2d>& points, const Pose2& initial,
                  const std::optional<CorrelativeWindow>& window) const;
  double Score(Query& q, int rotation, int dx, int dy, int level) const;
  std::optional<CorrelativeMatch> Result(const Query& q, const Candidate& best,
                                         const Pose2& initial, long* scored) const;
  void Search(Query& q, const Candidate& c, Candidate* best) const;

  CorrelativeMatcherParams params_;
  double resolution_m_ = 0.0;
  int x0_ = 0, y0_ = 0, width_ = 0, height_ = 0;  // the map's written cells
  std::vector<Grid> levels_;
};

}  // namespace slamkit
