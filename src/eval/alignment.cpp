#include "slamkit/eval/alignment.hpp"

#include <cmath>
#include <stdexcept>

namespace slamkit {

// Closed form in 2D: the optimal rotation angle is atan2 of the summed cross and dot products of
// the centred point pairs.
RigidAlignment AlignPoints(std::span<const Eigen::Vector2d> from,
                           std::span<const Eigen::Vector2d> to) {
  if (from.size() != to.size()) throw std::invalid_argument("AlignPoints: sizes differ");
  if (from.empty()) return {};
  Eigen::Vector2d mean_from = Eigen::Vector2d::Zero(), mean_to = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    mean_from += from[i];
    mean_to += to[i];
  }
  mean_from /= static_cast<double>(from.size());
  mean_to /= static_cast<double>(to.size());
  double dot = 0.0, cross = 0.0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector2d a = from[i] - mean_from, b = to[i] - mean_to;
    dot += a.dot(b);
    cross += a.x() * b.y() - a.y() * b.x();
  }
  const double angle = from.size() > 1 ? std::atan2(cross, dot) : 0.0;
  const Pose2 rotation(0.0, 0.0, angle);
  const Eigen::Vector2d t = mean_to - rotation.TransformFrom(mean_from);
  RigidAlignment out{Pose2(t.x(), t.y(), angle), 0.0};
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    sum_sq += (out.transform.TransformFrom(from[i]) - to[i]).squaredNorm();
  }
  out.rmse_m = std::sqrt(sum_sq / static_cast<double>(from.size()));
  return out;
}

}  // namespace slamkit
