#include "slamkit/filters/grid_slam_factory.hpp"

#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

const std::vector<std::string>& GridBackendNames() {
  static const std::vector<std::string> names = {"rbpf", "graph"};
  return names;
}

GraphGridSlamParams EffectiveGraphParams(const GridSlamConfig& config) {
  GraphGridSlamParams p = config.graph;
  p.usable_range_m = config.rbpf.usable_range_m;
  p.misses_spare_scan_hits = config.rbpf.misses_spare_scan_hits;
  p.no_return_ray_length_m = config.rbpf.no_return_ray_length_m;
  p.grid = config.rbpf.grid;
  p.initial_pose = config.rbpf.initial_pose;
  p.seed = config.rbpf.seed;
  return p;
}

std::unique_ptr<GridSlam> MakeGridSlam(const GridSlamConfig& config) {
  switch (config.backend) {
    case GridBackend::kRbpf: {
      const OccupancyGrid check(config.rbpf.grid);  // a bad resolution or limit throws here
      return std::make_unique<RbpfGridSlam>(config.rbpf);
    }
    case GridBackend::kGraph:
      return std::make_unique<GraphGridSlam>(EffectiveGraphParams(config));
  }
  return nullptr;  // unreachable: every GridBackend is handled above
}

}  // namespace slamkit
