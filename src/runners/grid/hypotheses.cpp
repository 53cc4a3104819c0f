#include "slamkit/runners/grid/hypotheses.hpp"

namespace slamkit {

std::vector<HypothesisRow> HypothesisRows(const PredictiveGridSlam& slam,
                                          const OccupancyGrid& final_map,
                                          const StructurePredictorParams& predictor) {
  std::vector<HypothesisRow> rows;
  for (const HypothesisRecord& record : slam.records()) {
    HypothesisRow row{record, std::nullopt};
    if (record.hypothesis.predicted_cells > 0) {
      row.final_similarity = HypothesisSimilarity(record.hypothesis, Pose2(), final_map, predictor);
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

OccupancyGrid PredictedCells(const OccupancyGrid& map, const OccupancyGrid* layer) {
  OccupancyGrid out(map.params());
  if (layer == nullptr) return out;
  ForEachKnownCell(*layer, [&](const CellIndex& c, OccupancyGrid::CellValue v) {
    if (!map.IsKnown(c)) out.UpdateSteps(c, v);
  });
  return out;
}

OccupancyGrid WithPredictedCells(const OccupancyGrid& map, const OccupancyGrid& predicted) {
  OccupancyGrid out = map;
  ForEachKnownCell(predicted, [&](const CellIndex& c, OccupancyGrid::CellValue v) {
    if (!map.IsKnown(c)) out.UpdateSteps(c, v);
  });
  return out;
}

nlohmann::json HypothesisFateCounts(const std::vector<HypothesisRow>& rows) {
  nlohmann::json counts = nlohmann::json::object();
  for (HypothesisFate fate :
       {HypothesisFate::kNoStructure, HypothesisFate::kBelowThreshold, HypothesisFate::kActive,
        HypothesisFate::kExplored, HypothesisFate::kDroppedByRecovery}) {
    counts[HypothesisFateName(fate)] = 0;
  }
  for (const HypothesisRow& row : rows) {
    nlohmann::json& count = counts[HypothesisFateName(row.record.fate)];
    count = count.get<int>() + 1;
  }
  return counts;
}

}  // namespace slamkit
