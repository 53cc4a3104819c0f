#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/pose2.hpp"
#include "slamkit/features/grid_structure.hpp"
#include "slamkit/filters/grid/predictive_grid_slam.hpp"
#include "slamkit/filters/grid/structure_hypothesis.hpp"
#include "slamkit/maps/occupancy_grid.hpp"
#include "slamkit/planning/grid_frontiers.hpp"
#include "slamkit/planning/grid_paths.hpp"

namespace slamkit {

// P-SLAM's environmental-structure predictor (SPEC S4, steps 2-4; seed 004, Section III).
struct StructurePredictorParams {
  // d: the target region S_f and the hypothesis lie within d / 2 of the target cell f (the seed's
  // Fig. 1 draws them as a circle of diameter d; its d is 10 m).
  double region_diameter_m = 10.0;
  // The target control point is the corner nearest f within this; none: no prediction (seed
  // III-A: "we search for the nearest corner feature as the control point in a preset range").
  // d / 2: any corner of S_f. A frontier lies where the laser's view ends, typically 3.5–5 m
  // from the nearest corner seen in SPEC S4's maze, so 3 m left most targets without one.
  double control_point_range_m = 5.0;
  // The search's budget: candidate corners within this of f, at most max_candidates of them,
  // nearest the control point first (the seed's "fixed searching bound").
  double search_radius_m = 30.0;
  int max_candidates = 100;
  // A candidate closer than this to the control point would align the target region with itself.
  double min_reference_distance_m = 2.0;
  // The seed's threshold: 0.4 to 0.7, 0.7 "with no a priori information".
  double similarity_threshold = 0.7;
  // Ψ counts an occupied cell as shared when the other region has one within this many cells: a
  // rotated one-cell-thin wall lands beside its match as often as on it. 0: Eq. 5 exactly.
  int tolerance_cells = 1;
  int min_structure_cells = 30;   // S_f needs this many occupied cells to be compared at all
  int min_predicted_cells = 20;   // a smaller hypothesis is not worth the particles' while
  double occupied_probability = 0.65;  // a cell above this is occupied (map_server's threshold)
  GridStructureParams structure;
  // Where the predictor picks f itself (a log has no explorer): the nearest reachable frontier.
  GridFrontierParams frontiers;
  GridPathParams paths;
};

// Γ of seed Eq. 2 as a rigid motion taking the reference control point onto the target one,
// with the reference turned by θ: x ↦ R(θ)(x − reference) + target.
Pose2 ControlPointAlignment(const Eigen::Vector2d& target_m, const Eigen::Vector2d& reference_m,
                            double theta_rad);

// Seed Eq. 5 between the region of `map` within `radius_m` of `center_m` (S: its known cells)
// and the same map seen through `alignment` (C̃: the cells x with alignment ⊕ x in the region, on
// a cell S knows): 2 |occ(S) ∩ occ(C̃)| / (|occ(S)| + |occ(C̃)|), with the tolerance above; 0 when
// neither has an occupied cell.
double AlignedSimilarity(const OccupancyGrid& map, const Eigen::Vector2d& center_m,
                         double radius_m, const Pose2& alignment,
                         const StructurePredictorParams& params);

// Steps 2-4 at the target point f: None when there is no control point near f or too little
// structure around it; otherwise the best alignment's hypothesis (accepted when its Ψ reaches
// the threshold and it predicts enough cells). Its cells are unknown in `map`, within d / 2 of f.
std::optional<PredictedStructure> PredictStructure(const OccupancyGrid& map,
                                                   const Eigen::Vector2d& target_m,
                                                   const StructurePredictorParams& params = {});

// Step 1 on a log: the nearest reachable frontier cell from `pose` (None: none), a cell of a
// region FindFrontierRegions keeps; of cells at one cost, the first the search settles.
std::optional<Eigen::Vector2d> ChoosePredictionTarget(const OccupancyGrid& map, const Pose2& pose,
                                                      const StructurePredictorParams& params);

// The predictor PredictiveGridSlam runs on its thread.
StructurePredictor MakeStructurePredictor(const StructurePredictorParams& params);

// Ψ between a hypothesis (seen through `to_map`) and `map` over the hypothesis's cells that `map`
// knows: how well it predicted what was explored later. None when `map` knows none of them.
std::optional<double> HypothesisSimilarity(const GridHypothesis& h, const Pose2& to_map,
                                           const OccupancyGrid& map,
                                           const StructurePredictorParams& params = {});

}  // namespace slamkit
