#include "slamkit/planning/structure_predictor.hpp"

#include <algorithm>
#include <cmath>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

float OccupiedLogOdds(double probability) {
  return static_cast<float>(std::log(probability / (1.0 - probability)));
}

bool OccupiedNear(const OccupancyGrid& grid, const CellIndex& c, int tolerance, float occupied) {
  for (int dy = -tolerance; dy <= tolerance; ++dy) {
    for (int dx = -tolerance; dx <= tolerance; ++dx) {
      if (grid.LogOdds({c.x + dx, c.y + dy}) > occupied) return true;
    }
  }
  return false;
}

// The centres of the occupied cells of `map` within `radius_m` of `center_m`, row by row; only
// the disc's box, clipped to the written cells, is read.
std::vector<Eigen::Vector2d> OccupiedCentres(const OccupancyGrid& map,
                                             const Eigen::Vector2d& center_m, double radius_m,
                                             float occupied) {
  std::vector<Eigen::Vector2d> cells;
  const Eigen::Vector2d reach(radius_m, radius_m);
  const CellIndex lo = map.WorldToCell(center_m - reach), hi = map.WorldToCell(center_m + reach);
  const CellIndex a = map.min_cell(), b = map.max_cell();
  for (int y = std::max(lo.y, a.y); y <= std::min(hi.y, b.y); ++y) {
    for (int x = std::max(lo.x, a.x); x <= std::min(hi.x, b.x); ++x) {
      const Eigen::Vector2d p = map.CellCenter({x, y});
      if ((p - center_m).norm() <= radius_m && map.LogOdds({x, y}) > occupied) cells.push_back(p);
    }
  }
  return cells;
}

// Eq. 5 with S's occupied cells given (see AlignedSimilarity).
double Similarity(const OccupancyGrid& map, const std::vector<Eigen::Vector2d>& target_occupied,
                  const Eigen::Vector2d& center_m, double radius_m, const Pose2& alignment,
                  const StructurePredictorParams& params) {
  const float occupied = OccupiedLogOdds(params.occupied_probability);
  const int tolerance = params.tolerance_cells;
  int matched = 0;
  for (const Eigen::Vector2d& s : target_occupied) {
    matched += OccupiedNear(map, map.WorldToCell(alignment.TransformTo(s)), tolerance, occupied);
  }
  int reference_occupied = 0;
  const Eigen::Vector2d preimage = alignment.TransformTo(center_m);
  for (const Eigen::Vector2d& x : OccupiedCentres(map, preimage, radius_m, occupied)) {
    const Eigen::Vector2d y = alignment.TransformFrom(x);
    const CellIndex c = map.WorldToCell(y);
    if ((y - center_m).norm() > radius_m || !map.IsKnown(c)) continue;
    ++reference_occupied;
    matched += OccupiedNear(map, c, tolerance, occupied);
  }
  const int total = static_cast<int>(target_occupied.size()) + reference_occupied;
  return total == 0 ? 0.0 : double(matched) / total;
}

struct Alignment {
  double similarity = -1.0;
  Pose2 pose;
  Eigen::Vector2d reference_m = Eigen::Vector2d::Zero();
  double theta_rad = 0.0;
  int evaluated = 0;
};

// SPEC S4 step 3: every candidate corner, each of the 4 pairings of the two corners' line
// angles (seed Fig. 4), scored by Ψ; the best kept (the first of equals).
Alignment BestAlignment(const OccupancyGrid& map, const GridCorner& control,
                        const std::vector<GridCorner>& candidates,
                        const std::vector<Eigen::Vector2d>& target_occupied,
                        const Eigen::Vector2d& f, const StructurePredictorParams& params) {
  Alignment best;
  const double radius = 0.5 * params.region_diameter_m;
  for (const GridCorner& candidate : candidates) {
    for (double phi_target : control.line_angles_rad) {
      for (double phi_reference : candidate.line_angles_rad) {
        const double theta = WrapAngle(phi_target - phi_reference);
        const Pose2 gamma =
            ControlPointAlignment(control.position_m, candidate.position_m, theta);
        const double psi = Similarity(map, target_occupied, f, radius, gamma, params);
        ++best.evaluated;
        if (psi > best.similarity) {
          best.similarity = psi, best.pose = gamma, best.theta_rad = theta;
          best.reference_m = candidate.position_m;
        }
      }
    }
  }
  return best;
}

// The corners to try: not the control point's own surroundings, within the search radius of f,
// nearest the control point first, at most max_candidates.
std::vector<GridCorner> Candidates(const std::vector<GridCorner>& corners,
                                   const GridCorner& control, const Eigen::Vector2d& f,
                                   const StructurePredictorParams& params) {
  std::vector<GridCorner> kept;
  for (const GridCorner& c : corners) {
    if ((c.position_m - control.position_m).norm() >= params.min_reference_distance_m &&
        (c.position_m - f).norm() <= params.search_radius_m) {
      kept.push_back(c);
    }
  }
  std::stable_sort(kept.begin(), kept.end(), [&](const GridCorner& a, const GridCorner& b) {
    return (a.position_m - control.position_m).squaredNorm() <
           (b.position_m - control.position_m).squaredNorm();
  });
  if (static_cast<int>(kept.size()) > params.max_candidates) kept.resize(params.max_candidates);
  return kept;
}

// Step 4: the aligned reference's known cells on the cells of the region `map` has not explored.
void FillHypothesis(const OccupancyGrid& map, const Eigen::Vector2d& f, const Pose2& gamma,
                    const StructurePredictorParams& params, GridHypothesis& h) {
  const double radius = 0.5 * params.region_diameter_m;
  const float occupied = OccupiedLogOdds(params.occupied_probability);
  const CellIndex lo = map.WorldToCell(f - Eigen::Vector2d(radius, radius));
  const CellIndex hi = map.WorldToCell(f + Eigen::Vector2d(radius, radius));
  for (int y = lo.y; y <= hi.y; ++y) {
    for (int x = lo.x; x <= hi.x; ++x) {
      const CellIndex c{x, y};
      const Eigen::Vector2d p = map.CellCenter(c);
      if ((p - f).norm() > radius || map.IsKnown(c)) continue;
      const CellIndex source = map.WorldToCell(gamma.TransformTo(p));
      const OccupancyGrid::CellValue v = map.LogOddsSteps(source);
      if (v == 0) continue;
      h.cells.UpdateSteps(c, v);
      ++h.predicted_cells;
      h.occupied_cells += map.LogOdds(source) > occupied;
    }
  }
}

}  // namespace

// Seed Eq. 2.
Pose2 ControlPointAlignment(const Eigen::Vector2d& target_m, const Eigen::Vector2d& reference_m,
                            double theta_rad) {
  const Pose2 turn(0.0, 0.0, theta_rad);
  const Eigen::Vector2d t = target_m - turn.TransformFrom(reference_m);
  return {t.x(), t.y(), theta_rad};
}

double AlignedSimilarity(const OccupancyGrid& map, const Eigen::Vector2d& center_m,
                         double radius_m, const Pose2& alignment,
                         const StructurePredictorParams& params) {
  const float occupied = OccupiedLogOdds(params.occupied_probability);
  return Similarity(map, OccupiedCentres(map, center_m, radius_m, occupied), center_m, radius_m,
                    alignment, params);
}

// SPEC S4, steps 2-4 (seed Section III).
std::optional<PredictedStructure> PredictStructure(const OccupancyGrid& map,
                                                   const Eigen::Vector2d& target_m,
                                                   const StructurePredictorParams& params) {
  const double radius = 0.5 * params.region_diameter_m;
  const std::vector<GridCorner> corners = ExtractGridCorners(
      ExtractGridLines(map, target_m, params.search_radius_m + radius, params.structure),
      params.structure);
  const GridCorner* control = nullptr;
  for (const GridCorner& c : corners) {
    const double distance = (c.position_m - target_m).norm();
    if (distance <= params.control_point_range_m &&
        (control == nullptr || distance < (control->position_m - target_m).norm())) {
      control = &c;
    }
  }
  if (control == nullptr) return std::nullopt;
  const std::vector<Eigen::Vector2d> target_occupied =
      OccupiedCentres(map, target_m, radius, OccupiedLogOdds(params.occupied_probability));
  if (static_cast<int>(target_occupied.size()) < params.min_structure_cells) return std::nullopt;
  const std::vector<GridCorner> candidates = Candidates(corners, *control, target_m, params);
  if (candidates.empty()) return std::nullopt;
  const Alignment best =
      BestAlignment(map, *control, candidates, target_occupied, target_m, params);
  PredictedStructure result{GridHypothesis{.target_m = target_m,
                                           .control_point_m = control->position_m,
                                           .reference_point_m = best.reference_m,
                                           .rotation_rad = best.theta_rad,
                                           .similarity = best.similarity,
                                           .alignments = best.evaluated,
                                           .cells = OccupancyGrid(map.params())},
                            false};
  if (best.similarity < params.similarity_threshold) return result;
  FillHypothesis(map, target_m, best.pose, params, result.hypothesis);
  result.accepted = result.hypothesis.predicted_cells >= params.min_predicted_cells;
  if (!result.accepted) {
    result.hypothesis.cells = OccupancyGrid(map.params());
    result.hypothesis.predicted_cells = result.hypothesis.occupied_cells = 0;
  }
  return result;
}

// The search stops at the first frontier cell it settles; only the frontiers it meets are looked
// at (a map's frontiers fill the whole window where beams ran out into unknown space).
std::optional<Eigen::Vector2d> ChoosePredictionTarget(const OccupancyGrid& map, const Pose2& pose,
                                                      const StructurePredictorParams& params) {
  const auto is_goal = [&](const CellIndex& c) {
    return InFrontierRegion(map, c, params.frontiers);
  };
  const GridPathCosts costs =
      GridPathCosts::UpToNearestGoal(map, pose.translation(), is_goal, params.paths);
  if (!costs.goal()) return std::nullopt;
  return map.CellCenter(*costs.goal());
}

StructurePredictor MakeStructurePredictor(const StructurePredictorParams& params) {
  return [params](const StructurePredictionRequest& request)
             -> std::optional<PredictedStructure> {
    const std::optional<Eigen::Vector2d> target =
        request.target_m ? request.target_m
                         : ChoosePredictionTarget(request.map, request.pose, params);
    if (!target) return std::nullopt;
    std::optional<PredictedStructure> result = PredictStructure(request.map, *target, params);
    if (!result) {  // keep where it looked
      result.emplace();
      result->hypothesis.target_m = *target;
      result->structure_found = false;
    }
    result->hypothesis.t_s = request.t_s;
    return result;
  };
}

std::optional<double> HypothesisSimilarity(const GridHypothesis& h, const Pose2& to_map,
                                           const OccupancyGrid& map,
                                           const StructurePredictorParams& params) {
  const float occupied = OccupiedLogOdds(params.occupied_probability);
  const int tolerance = params.tolerance_cells;
  int compared = 0, total = 0, matched = 0;
  ForEachKnownCell(h.cells, [&](const CellIndex& c, OccupancyGrid::CellValue) {
    const CellIndex m = map.WorldToCell(to_map.TransformFrom(h.cells.CellCenter(c)));
    if (!map.IsKnown(m)) return;
    ++compared;
    if (h.cells.LogOdds(c) > occupied) {
      ++total;
      matched += OccupiedNear(map, m, tolerance, occupied);
    }
    if (map.LogOdds(m) > occupied) {
      ++total;
      matched += OccupiedNear(h.cells, c, tolerance, occupied);
    }
  });
  if (compared == 0) return std::nullopt;
  return total == 0 ? 0.0 : double(matched) / total;
}

}  // namespace slamkit
