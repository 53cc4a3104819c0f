#include "slamkit/filters/graph/submaps.hpp"

#include <stdexcept>

namespace slamkit {

SubmapStack::SubmapStack(const SubmapParams& params, const OccupancyGridParams& grid,
                         const ScanInsertionParams& insertion)
    : params_(params), grid_(grid), insertion_(insertion) {
  if (params.nodes_per_submap < 1) {
    throw std::invalid_argument("submaps: nodes_per_submap must be at least 1");
  }
  const OccupancyGrid check(grid);  // a bad resolution or limit throws here
}

const Submap* SubmapStack::MatchingSubmap() const {
  return active_.empty() ? nullptr : submaps_[static_cast<std::size_t>(active_.front())].get();
}

// Hess et al. 2016, Section IV: a submap is started every N nodes and finished after 2N.
std::vector<std::shared_ptr<const Submap>> SubmapStack::Insert(int node, const Pose2& pose,
                                                               const LaserScan& scan) {
  if (inserted_ % params_.nodes_per_submap == 0) {
    auto submap = std::make_shared<Submap>();
    submap->index = static_cast<int>(submaps_.size());
    submap->origin_node = node;
    submap->origin = pose;
    submap->grid = OccupancyGrid(grid_);
    active_.push_back(submap->index);
    submaps_.push_back(std::move(submap));
  }
  ++inserted_;
  const Pose2 laser = pose.Compose(scan.laser_offset);
  std::vector<std::shared_ptr<const Submap>> finished;
  for (const int i : active_) {
    Submap& s = *submaps_[static_cast<std::size_t>(i)];
    InsertScan(s.grid, laser, scan, insertion_);
    s.nodes.push_back(node);
    s.poses.push_back(pose);
    if (static_cast<int>(s.nodes.size()) >= 2 * params_.nodes_per_submap) {
      s.finished = true;
      finished.push_back(submaps_[static_cast<std::size_t>(i)]);
    }
  }
  std::erase_if(active_, [this](int i) { return submaps_[static_cast<std::size_t>(i)]->finished; });
  return finished;
}

std::vector<std::shared_ptr<const Submap>> SubmapStack::FinishAll() {
  std::vector<std::shared_ptr<const Submap>> finished;
  for (const int i : active_) {
    submaps_[static_cast<std::size_t>(i)]->finished = true;
    finished.push_back(submaps_[static_cast<std::size_t>(i)]);
  }
  active_.clear();
  return finished;
}

}  // namespace slamkit
