#pragma once

#include <memory>
#include <vector>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

// A local map of a stretch of consecutive graph nodes, in the frame of the front end's local
// poses: its cells are where the front end put the scans, so it stays a consistent piece of map
// however the graph later moves it. Immutable once finished, so the loop-closure search can read
// it from another thread while the front end builds the next ones.
struct Submap {
  int index = 0;
  int origin_node = 0;  // the first node inserted: the submap's pose in the graph is this node's
  Pose2 origin;         // that node's local pose
  OccupancyGrid grid;   // in the local frame (not the origin's)
  std::vector<int> nodes;                 // the nodes inserted, in order
  std::vector<Pose2> poses;  // their local poses
  bool finished = false;
};

struct SubmapParams {
  // A new submap is started every this many nodes, and each takes twice as many, so the front
  // end always matches against a submap that holds at least this many (Hess et al. 2016,
  // Section IV: two submaps active at a time, the older one matched against).
  int nodes_per_submap = 60;
};

// The submaps of a run: every node's scan goes into the one or two active submaps; the older
// one is what a new scan is matched against; a submap that holds 2 × nodes_per_submap nodes is
// finished.
class SubmapStack {
 public:
  // Throws std::invalid_argument for nodes_per_submap < 1 or grid params an OccupancyGrid cannot
  // take.
  SubmapStack(const SubmapParams& params, const OccupancyGridParams& grid,
              const ScanInsertionParams& insertion);

  // The submap the next scan is matched against (null before the first insertion).
  const Submap* MatchingSubmap() const;
  // Inserts node `node`'s scan at local pose `pose` into the active submaps, starting a new one
  // when due; returns the submaps this insertion finished.
  std::vector<std::shared_ptr<const Submap>> Insert(int node, const Pose2& pose,
                                                    const LaserScan& scan);
  // Finishes the active submaps (at the end of a run), returning them.
  std::vector<std::shared_ptr<const Submap>> FinishAll();

  const std::vector<std::shared_ptr<Submap>>& all() const { return submaps_; }

 private:
  SubmapParams params_;
  OccupancyGridParams grid_;
  ScanInsertionParams insertion_;
  std::vector<std::shared_ptr<Submap>> submaps_;
  std::vector<int> active_;  // indices into submaps_, oldest first
  int inserted_ = 0;         // nodes inserted so far
};

}  // namespace slamkit
