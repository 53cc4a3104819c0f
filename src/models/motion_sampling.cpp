#include "slamkit/models/motion_sampling.hpp"

namespace slamkit {

Pose2 SampleMotion(const MotionModel& model, const Pose2& x, const Control& u, double dt_s,
                   Rng& rng, const ControlCovariance* control_noise) {
  const ControlCovariance Q = control_noise ? *control_noise : model.Noise(u, dt_s);
  const Control noisy = u + rng.MultivariateNormal(Q);
  return model.Move(x, noisy, dt_s);
}

}  // namespace slamkit
