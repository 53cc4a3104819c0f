#include "slamkit/models/odometry_sampling.hpp"

#include <cmath>

#include "slamkit/core/angle.hpp"

namespace slamkit {

Eigen::Vector3d OdometryNoiseSigmas(const Pose2& delta, const OdometryNoiseParams& noise) {
  const double dx = std::abs(delta.x()), dy = std::abs(delta.y());
  const double dth = std::abs(delta.theta());
  // GMapping couples the two translation axes weakly (0.3 srr) so a sideways slip stays possible.
  const double sxy = 0.3 * noise.srr;
  return {noise.srr * dx + noise.srt * dth + sxy * dy, noise.srr * dy + noise.srt * dth + sxy * dx,
          noise.stt * dth + noise.str * std::hypot(dx, dy)};
}

double OdometryMotionLogDensity(const Pose2& from, const Pose2& delta, const Pose2& to,
                                const OdometryNoiseParams& noise) {
  const Eigen::Vector3d sigma =
      OdometryNoiseSigmas(delta, noise).cwiseMax(Eigen::Vector3d(1e-3, 1e-3, 1e-3));
  const Pose2 moved = from.Between(to);
  const Eigen::Vector3d n(moved.x() - delta.x(), moved.y() - delta.y(),
                          WrapAngle(moved.theta() - delta.theta()));
  return -0.5 * n.cwiseQuotient(sigma).squaredNorm();
}

Pose2 SampleOdometryMotion(const Pose2& pose, const Pose2& delta, const OdometryNoiseParams& noise,
                           Rng& rng) {
  const Eigen::Vector3d sigma = OdometryNoiseSigmas(delta, noise);
  const double nx = rng.Normal(0.0, sigma.x());
  const double ny = rng.Normal(0.0, sigma.y());
  const double nt = rng.Normal(0.0, sigma.z());
  return pose.Compose(Pose2(delta.x() + nx, delta.y() + ny, delta.theta() + nt));
}

}  // namespace slamkit
