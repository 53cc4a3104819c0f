#pragma once

// The figures of `slamkit explore` and `explore --compare`: the runners' results as the report
// module's figure data.

#include <filesystem>
#include <string>
#include <vector>

#include "slamkit/report/figures.hpp"
#include "slamkit/runners/features/explore_compare.hpp"

namespace slamkit::app {

// The line map of one run: the plan's true walls, the scan points, the mapped lines' seen
// extents, the corners and the true, estimated and odometry paths.
LineMapFigureData LineMapOf(const FloorPlan& plan, const ExploreResult& result,
                            const std::string& title);

// DIR/slam_time.png (accumulated SLAM time over simulated time, first seed, one curve per
// policy), DIR/nees.png (ANEES per step per policy with the 95 % band for all runs) and
// DIR/map_<policy>.png (LineMapOf the first seed).
void WriteCompareFigures(const std::filesystem::path& dir, const FloorPlan& plan,
                         const ExploreCompareResult& result, std::uint64_t first_seed);

}  // namespace slamkit::app
