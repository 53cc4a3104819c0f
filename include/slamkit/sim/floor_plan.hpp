#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "slamkit/maps/occupancy_image.hpp"
#include "slamkit/maps/walls.hpp"

namespace slamkit {

class WallGrid;  // the walls bucketed into square cells (floor_plan.cpp)

// A FloorPlan's ray-casting index, built on first use and shared by every later cast. It is
// rebuilt when `walls` changes size or storage; after editing walls in place, call Reset(). A copy
// starts empty because the copy's walls may then be edited on their own. Thread-safe.
class WallIndexCache {
 public:
  WallIndexCache() = default;
  WallIndexCache(const WallIndexCache& /*other*/) {}
  WallIndexCache& operator=(const WallIndexCache& other);

  // The index of `walls`: the cached one, or a new one when `walls` is not the vector it was built
  // from. Never null.
  std::shared_ptr<const WallGrid> Get(const std::vector<WallSegment>& walls) const;
  void Reset();

 private:
  mutable std::mutex mutex_;
  mutable std::shared_ptr<const WallGrid> grid_;
  mutable const WallSegment* built_from_data_ = nullptr;
  mutable std::size_t built_from_size_ = 0;
};

// A planar world of walls for the laser simulator (SPEC S4). Build it as FloorPlan{walls}.
struct FloorPlan {
  std::vector<WallSegment> walls;
  WallIndexCache ray_index = {};  // see WallIndexCache for when to Reset() it
};

// Casts many rays against one plan: takes the plan's index once, then each ray walks only the
// grid cells it crosses (brute force over all walls for plans of fewer than 64 walls, where that is
// faster). The plan must outlive the caster.
class RayCaster {
 public:
  explicit RayCaster(const FloorPlan& plan);
  // See CastRay.
  double Cast(const Eigen::Vector2d& origin_m, const Eigen::Vector2d& unit_direction,
              double max_range_m) const;

 private:
  const FloorPlan* plan_;
  std::shared_ptr<const WallGrid> grid_;  // null: brute force
};

// Distance in metres from `origin_m` along `unit_direction` to the first wall, or max_range_m when
// no wall lies closer. Walls are closed segments (a ray through an end point hits it); a wall seen
// exactly edge-on is not hit, nor is a wall through the origin itself.
double CastRay(const FloorPlan& plan, const Eigen::Vector2d& origin_m,
               const Eigen::Vector2d& unit_direction, double max_range_m);
// The same by testing every wall: the reference CastRay must agree with, bit for bit.
double CastRayBruteForce(const FloorPlan& plan, const Eigen::Vector2d& origin_m,
                         const Eigen::Vector2d& unit_direction, double max_range_m);

// SPEC S4's symmetric maze: a square outer wall around a square array of square blocks, with
// corridors of equal width between the blocks and between the blocks and the outer wall. The
// defaults give 4 × 4 blocks (2.2 + 4 × 3.5 + 3 × 2.2 + 2.2 = 25).
struct SquareMazeParams {
  double outer_size_m = 25.0;      // side of the outer wall
  double block_size_m = 3.5;       // side of each block
  double corridor_width_m = 2.2;   // the least corridor width; leftover space widens the outer ring
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // lower-left corner of the outer wall
};

FloorPlan MakeSquareMaze(const SquareMazeParams& params = {});

// The walls of an occupancy image: every pixel edge between an occupied pixel and a free one (or
// the outside of the image), with collinear consecutive edges merged into one segment. A pixel is
// occupied when its value is below `occupied_below` (dark = occupied, as in map_server images).
FloorPlan FloorPlanFromOccupancy(const OccupancyImage& image, std::uint8_t occupied_below = 128);

}  // namespace slamkit
