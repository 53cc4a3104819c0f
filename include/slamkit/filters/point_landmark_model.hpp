#pragma once

#include "slamkit/filters/observation_model.hpp"
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

 private:
  const PointSensorModel* sensor_;
  int point_kind_;
  double margin_m_;
};

}  // namespace slamkit
