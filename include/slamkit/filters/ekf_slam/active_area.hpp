#pragma once

#include <Eigen/Core>
#include <functional>
#include <span>

#include "slamkit/filters/ekf/block_ekf.hpp"

namespace slamkit {

// How the block EKF's updates touch the covariance.
enum class EkfUpdateMode {
  kDense,       // every update touches the whole state (O(n²) per scan)
  kCompressed,  // updates touch the active area; the rest waits for a global update
};

// The active area of compressed updates (Guivant & Nebot, IEEE T-RA 2001, Sec. IV): a disc around
// the pose where it was opened, holding every landmark the vehicle can reach while it stays
// within `hysteresis_fraction` of its reach (sensor range plus association margin) of the
// centre. Leaving that disc opens a new area around the pose (one global update). Nothing here
// depends on the world: the radii scale with the sensor.
struct ActiveAreaParams {
  // How far the vehicle may go from the centre before a new area, as a fraction of its reach:
  // larger means fewer global updates (O(n²·a) each) but a larger area (O(a²) per update).
  double hysteresis_fraction = 0.5;
  // The area is widened by this many standard deviations of the position (largest axis), so
  // that landmarks whose means move with a correction stay within it.
  double sigma_factor = 3.0;
};

// What the compressed updates cost in a run.
struct CompressionStats {
  long global_updates = 0;     // areas closed (each an O(n²·a) update)
  double global_update_s = 0;  // wall time spent in them
  int max_active_size = 0;     // largest area's state entries
};

// The squared distance from a landmark block to a point: from a point landmark's mean, from
// what has been seen of a line.
using LandmarkDistanceSq = std::function<double(int block, const Eigen::Vector2d& point)>;

// Keeps a BlockEkf's active area around one pose among landmarks.
class ActiveArea {
 public:
  explicit ActiveArea(const ActiveAreaParams& params) : params_(params) {}

  // Before a scan: keeps the open area while the pose is within the hysteresis of its centre,
  // else synchronises and opens a new one around the pose from the `landmarks` blocks within
  // its radius by `distance_sq`.
  void Maintain(BlockEkf& ekf, int pose_block, std::span<const int> landmarks, double reach_m,
                const LandmarkDistanceSq& distance_sq);
  // The same among point landmarks (2-dim blocks whose mean is the position).
  void Maintain(BlockEkf& ekf, int pose_block, std::span<const int> points, double reach_m);
  // The global update (before output, or when the mode changes).
  void Synchronise(BlockEkf& ekf);
  void Reset() { stats_ = {}; }
  const CompressionStats& stats() const { return stats_; }

 private:
  ActiveAreaParams params_;
  Eigen::Vector2d centre_ = Eigen::Vector2d::Zero();
  CompressionStats stats_;
};

}  // namespace slamkit
