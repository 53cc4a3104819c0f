#pragma once

#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "slamkit/filters/grid/predictive_grid_slam.hpp"
#include "slamkit/planning/structure_predictor.hpp"

namespace slamkit {

// One P-SLAM hypothesis as hypotheses.csv lists it (SPEC S4): the request and what became of it.
struct HypothesisRow {
  HypothesisRecord record;
  // Ψ (Eq. 5) of h against the finally built map, over the cells of h that map knows: how well
  // it predicted what was explored later. Unset when nothing was predicted or none was explored.
  std::optional<double> final_similarity;
};

// The rows of every request `slam` made, scored against `final_map`. h lies in the frame of the
// best map at its request, taken here as final_map's (the map frames of the best particles of
// one run differ by the filter's error only).
std::vector<HypothesisRow> HypothesisRows(const PredictiveGridSlam& slam,
                                          const OccupancyGrid& final_map,
                                          const StructurePredictorParams& predictor);

// The cells of `layer` (null: none) where `map` is unknown: what the best particle sees predicted.
OccupancyGrid PredictedCells(const OccupancyGrid& map, const OccupancyGrid* layer);

// `map` with the cells of `predicted` written where it is unknown.
OccupancyGrid WithPredictedCells(const OccupancyGrid& map, const OccupancyGrid& predicted);

// metrics.json's `hypotheses_by_fate`: a count per fate, every fate listed.
nlohmann::json HypothesisFateCounts(const std::vector<HypothesisRow>& rows);

// The P-SLAM part of a run's configuration.
struct GridPredictionConfig {
  bool predict = false;
  PredictiveGridSlamParams prediction;
  StructurePredictorParams predictor;
};

}  // namespace slamkit
