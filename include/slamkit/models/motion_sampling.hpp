#pragma once

#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/models/motion_model.hpp"

namespace slamkit {

// A sample of the motion model for particle filters (Probabilistic Robotics Table 5.3 for a
// model with Gaussian control noise): draws the control from N(u, Q) and moves `x` with it. Q is
// the model's noise for (u, dt_s) unless `control_noise` overrides it.
Pose2 SampleMotion(const MotionModel& model, const Pose2& x, const Control& u, double dt_s,
                   Rng& rng, const ControlCovariance* control_noise = nullptr);

}  // namespace slamkit
