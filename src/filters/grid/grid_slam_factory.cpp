#include "slamkit/filters/grid/grid_slam_factory.hpp"

#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

const std::vector<std::string>& GridBackendNames() {
  static const std::vector<std::string> names = {"rbpf"};
  return names;
}

std::unique_ptr<GridSlam> MakeGridSlam(const GridSlamConfig& config) {
  switch (config.backend) {
    case GridBackend::kRbpf: {
      const OccupancyGrid check(config.rbpf.grid);  // a bad resolution or limit throws here
      return std::make_unique<RbpfGridSlam>(config.rbpf);
    }
  }
  return nullptr;  // unreachable: every GridBackend is handled above
}

}  // namespace slamkit
