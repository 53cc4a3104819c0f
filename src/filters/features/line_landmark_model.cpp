#include "slamkit/filters/features/line_landmark_model.hpp"

#include <numbers>

namespace slamkit {

BlockKind LineBlockKind() {
  BlockKind kind;
  kind.dim = 2;
  kind.angle_components = {1};
  kind.is_pose = false;
  kind.normalise = &NormaliseLineBlock;
  return kind;
}

// SPEC S1: a world line's state stays in Hessian normal form, ρ ≥ 0.
bool NormaliseLineBlock(BlockVector& mean, BlockMatrix* J) {
  PolarLine line = LineOf(mean);
  const bool flipped = NormaliseLine(&line);
  line.alpha_rad = WrapLineAngle(line.alpha_rad);
  if (!flipped && line.alpha_rad == mean[1]) return false;
  mean = LineVector(line);
  *J = BlockMatrix::Identity(2, 2);
  if (flipped) (*J)(0, 0) = -1.0;
  return true;
}

PolarLine LineOf(const BlockVector& mean) { return {mean[0], mean[1]}; }

BlockVector LineVector(const PolarLine& line) {
  BlockVector v(2);
  v << line.rho_m, line.alpha_rad;
  return v;
}

BlockPrediction LineLandmarkModel::Predict(const BlockEkf& ekf, std::span<const int> blocks) const {
  Eigen::Matrix<double, 2, 3> J_z_x;
  Eigen::Matrix2d J_z_l;
  BlockPrediction out;
  out.z =
      LineVector(PredictLine(ekf.PoseOf(blocks[0]), LineOf(ekf.Mean(blocks[1])), &J_z_x, &J_z_l));
  out.J_z_blocks.Add(blocks[0], J_z_x);
  out.J_z_blocks.Add(blocks[1], J_z_l);
  return out;
}

BlockVector LineLandmarkModel::Innovation(const BlockVector& z, const BlockVector& z_pred) const {
  return LineInnovation(LineOf(z), LineOf(z_pred));
}

BlockInversion LineLandmarkModel::Invert(const BlockEkf& ekf, std::span<const int> observers,
                                         const BlockVector& z) const {
  Eigen::Matrix<double, 2, 3> J_l_x;
  Eigen::Matrix2d J_l_z;
  BlockInversion out;
  out.mean = LineVector(InvertLine(ekf.PoseOf(observers[0]), LineOf(z), &J_l_x, &J_l_z));
  out.J_new_blocks.Add(observers[0], J_l_x);
  out.J_new_z = J_l_z;
  return out;
}

bool LineLandmarkModel::Gate(const BlockEkf& ekf, std::span<const int> blocks) const {
  return PredictLine(ekf.PoseOf(blocks[0]), LineOf(ekf.Mean(blocks[1]))).rho_m >= min_rho_m_;
}

}  // namespace slamkit
