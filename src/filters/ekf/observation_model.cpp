#include "slamkit/filters/ekf/observation_model.hpp"

#include <stdexcept>

namespace slamkit {

BlockInversion ObservationModel::Invert(const BlockEkf& /*ekf*/, std::span<const int> /*observers*/,
                                        const BlockVector& /*z*/) const {
  throw std::logic_error("ObservationModel::Invert: this model cannot initialise a block");
}

Linearisation Linearise(const ObservationModel& model, const BlockEkf& ekf,
                        std::span<const int> blocks, const BlockVector& z, const BlockMatrix& R) {
  const BlockPrediction prediction = model.Predict(ekf, blocks);
  return {model.Innovation(z, prediction.z), prediction.J_z_blocks, R};
}

int AugmentFrom(const ObservationModel& model, BlockEkf& ekf, std::span<const int> observers,
                const BlockVector& z, const BlockMatrix& R) {
  const BlockInversion inv = model.Invert(ekf, observers, z);
  return ekf.Augment(model.NewBlockKind(), inv.mean, inv.J_new_blocks.view(), inv.J_new_z, R);
}

}  // namespace slamkit
