#pragma once

#include "slamkit/filters/ekf/observation_model.hpp"
#include "slamkit/models/point_sensor.hpp"

namespace slamkit {

// A point-landmark sensor (range-bearing, relative point, …) as the observation model of the
// point kind: blocks are {observing pose, landmark}. The gate is a reach test: a landmark
// farther than the sensor's range plus `margin_m` from the pose cannot have been seen.
class PointLandmarkModel final : public ObservationModel {
 public:
  // `sensor` must outlive the model; `point_kind` is the BlockEkf kind of the landmarks.
  PointLandmarkModel(const PointSensorModel& sensor, int point_kind, double margin_m)
      : sensor_(&sensor), point_kind_(point_kind), margin_m_(margin_m) {}

  int MeasurementDim() const override { return 2; }
  BlockPrediction Predict(const BlockEkf& ekf, std::span<const int> blocks) const override;
  BlockVector Innovation(const BlockVector& z, const BlockVector& z_pred) const override;
  int NewBlockKind() const override { return point_kind_; }
  BlockInversion Invert(const BlockEkf& ekf, std::span<const int> observers,
                        const BlockVector& z) const override;
  bool Gate(const BlockEkf& ekf, std::span<const int> blocks) const override;

  // Gate() with the observer's position and the squared reach hoisted out of a candidate loop:
  // the same test, inline, without a virtual call per landmark.
  struct ReachGate {
    Eigen::Vector2d position;
    double reach_sq;
    bool Passes(const Eigen::Vector2d& l) const { return (l - position).squaredNorm() <= reach_sq; }
  };
  ReachGate GateFrom(const Pose2& observer) const;
  // Predict() and Innovation() at fixed sizes for association's fast path: fills the innovation
  // and Jacobians of `out` for `z` of landmark position `l` seen from `observer`.
  void LinearisePosePoint(const Pose2& observer, const Eigen::Vector2d& l,
                          const Eigen::Vector2d& z, PosePointObservation& out) const;

 private:
  const PointSensorModel* sensor_;
  int point_kind_;
  double margin_m_;
};

}  // namespace slamkit
