#include "slamkit/models/odometry_sampling.hpp"

#include <cmath>

namespace slamkit {

Pose2 SampleOdometryMotion(const Pose2& pose, const Pose2& delta, const OdometryNoiseParams& noise,
                           Rng& rng) {
  const double dx = std::abs(delta.x()), dy = std::abs(delta.y());
  const double dth = std::abs(delta.theta());
  // GMapping couples the two translation axes weakly (0.3 srr) so a sideways slip stays possible.
  const double sxy = 0.3 * noise.srr;
  const double nx = rng.Normal(0.0, noise.srr * dx + noise.srt * dth + sxy * dy);
  const double ny = rng.Normal(0.0, noise.srr * dy + noise.srt * dth + sxy * dx);
  const double nt = rng.Normal(0.0, noise.stt * dth + noise.str * std::hypot(dx, dy));
  return pose.Compose(Pose2(delta.x() + nx, delta.y() + ny, delta.theta() + nt));
}

}  // namespace slamkit
