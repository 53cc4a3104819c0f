#pragma once

#include <span>

#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit {

// h(x) at the current mean with its Jacobian with respect to every block it reads.
struct BlockPrediction {
  BlockVector z;
  BlockJacobians J_z_blocks;
};

// The block that produced a measurement, from the blocks that observed it (state augmentation):
// its mean and its Jacobians with respect to those blocks and to the measurement.
struct BlockInversion {
  BlockVector mean;
  BlockJacobians J_new_blocks;
  BlockMatrix J_new_z;
};

// How one kind of observation relates to the state blocks it involves (an observing pose and a
// landmark; two poses for a vehicle-vehicle sighting; one pose for a position fix). `blocks` are
// BlockEkf block indices in the order the model defines (observers first).
class ObservationModel {
 public:
  virtual ~ObservationModel() = default;

  virtual int MeasurementDim() const = 0;
  virtual BlockPrediction Predict(const BlockEkf& ekf, std::span<const int> blocks) const = 0;
  // z − ẑ with any angular component wrapped.
  virtual BlockVector Innovation(const BlockVector& z, const BlockVector& z_pred) const = 0;
  // The kind of block Invert() creates; -1 if the model cannot initialise one (a position fix).
  virtual int NewBlockKind() const { return -1; }
  // The new block that produced `z`, seen from `observers`. Only for NewBlockKind() >= 0.
  virtual BlockInversion Invert(const BlockEkf& ekf, std::span<const int> observers,
                                const BlockVector& z) const;
  // Whether `blocks` can have produced an observation at all (e.g. a landmark within reach), so
  // that association skips the Mahalanobis test on the rest.
  virtual bool Gate(const BlockEkf& /*ekf*/, std::span<const int> /*blocks*/) const { return true; }
};

// `z` (noise `R`) linearised under `model` at the current mean of `ekf`.
Linearisation Linearise(const ObservationModel& model, const BlockEkf& ekf,
                        std::span<const int> blocks, const BlockVector& z, const BlockMatrix& R);

// SPEC S2, Eq. 8: adds the block that produced `z` (noise `R`) seen from `observers`; returns
// its index.
int AugmentFrom(const ObservationModel& model, BlockEkf& ekf, std::span<const int> observers,
                const BlockVector& z, const BlockMatrix& R);

}  // namespace slamkit
