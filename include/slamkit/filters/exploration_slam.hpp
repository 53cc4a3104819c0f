#pragma once

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"

namespace slamkit {

// The SLAM a simulated robot explores with (SPEC S1, active loop): each step it gets the odometry
// increment since its last step and the scan, and gives back its pose estimate.
class ExplorationSlam {
 public:
  virtual ~ExplorationSlam() = default;
  // `odometry_delta` is in the robot frame of the previous step.
  virtual void Step(const Pose2& odometry_delta, const LaserScan& scan) = 0;
  virtual Pose2 Estimate() const = 0;
  // The last Step's cost in seconds as a model of its work (for SlamTiming::kModelledCost).
  virtual double ModelledCostS() const = 0;
};

}  // namespace slamkit
