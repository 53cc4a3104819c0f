#pragma once

#include "slamkit/filters/ekf/observation_model.hpp"
#include "slamkit/models/line_sensor.hpp"

namespace slamkit {

// The BlockEkf kind of a world line (ρ_w [m], α_w [rad]) (SPEC S1: lines as landmarks), kept
// canonical (ρ_w ≥ 0, α_w in (−π, π]) by NormaliseLineBlock.
BlockKind LineBlockKind();

// BlockNormaliser of the line kind: (ρ, α) with ρ < 0 becomes (−ρ, α + π), the same line, with
// J = diag(−1, 1); α is wrapped to (−π, π] either way (J = I if only that changed).
bool NormaliseLineBlock(BlockVector& mean, BlockMatrix* J);

// A world line seen from a pose as (ρ, α) in the robot frame (models/line_sensor.hpp) as the
// observation model of the line kind: blocks are {observing pose, line}. Measurements are
// PolarLine (ρ, α) with ρ ≥ 0, as feature extraction gives them, noise the segment's covariance.
//
// Near ρ ≈ 0 (the robot on or close to the line) the sign of the predicted ρ, and hence the
// side the flip of PredictLine picks, is decided by noise: a measurement taken on the other side
// would differ from the prediction by π in α and the innovation would be wrong. Gate() rejects a
// line whose predicted ρ is below `min_rho_m`, so such sightings are never associated (and never
// initialise a landmark: see LineAssociationParams), rather than produce that innovation.
class LineLandmarkModel final : public ObservationModel {
 public:
  LineLandmarkModel(int line_kind, double min_rho_m)
      : line_kind_(line_kind), min_rho_m_(min_rho_m) {}

  int MeasurementDim() const override { return 2; }
  BlockPrediction Predict(const BlockEkf& ekf, std::span<const int> blocks) const override;
  // (Δρ, Δα) with Δα wrapped to [−π, π).
  BlockVector Innovation(const BlockVector& z, const BlockVector& z_pred) const override;
  int NewBlockKind() const override { return line_kind_; }
  BlockInversion Invert(const BlockEkf& ekf, std::span<const int> observers,
                        const BlockVector& z) const override;
  // Whether the line's predicted ρ from the pose is at least min_rho_m (see above).
  bool Gate(const BlockEkf& ekf, std::span<const int> blocks) const override;

  double min_rho_m() const { return min_rho_m_; }

 private:
  int line_kind_;
  double min_rho_m_;
};

// A block's mean as a PolarLine, and back.
PolarLine LineOf(const BlockVector& mean);
BlockVector LineVector(const PolarLine& line);

}  // namespace slamkit
