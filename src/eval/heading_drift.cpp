#include "slamkit/eval/heading_drift.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "slamkit/core/angle.hpp"

namespace slamkit {
namespace {

struct Window {
  double distance_m = 0.0;
  double disagreement_rad = 0.0;  // the estimate's turn − the odometry's
};

std::vector<Window> Windows(std::span<const Pose2> odometry, const Trajectory& estimate,
                            int window_steps) {
  std::vector<Window> out;
  const std::size_t n = odometry.size() / static_cast<std::size_t>(window_steps);
  for (std::size_t w = 0; w < n; ++w) {
    Window window;
    for (std::size_t k = w * window_steps; k < (w + 1) * window_steps; ++k) {
      window.distance_m += odometry[k].translation().norm();
      const double estimate_turn =
          WrapAngle(estimate[k + 1].pose.theta() - estimate[k].pose.theta());
      window.disagreement_rad += estimate_turn - odometry[k].theta();
    }
    out.push_back(window);
  }
  return out;
}

}  // namespace

HeadingDriftFit FitHeadingDrift(std::span<const Pose2> odometry, const Trajectory& estimate,
                                const HeadingDriftParams& params) {
  if (estimate.size() != odometry.size() + 1) {
    throw std::invalid_argument("FitHeadingDrift: " + std::to_string(odometry.size()) +
                                " odometry steps need " + std::to_string(odometry.size() + 1) +
                                " estimated poses, got " + std::to_string(estimate.size()));
  }
  if (params.window_steps < 1) throw std::invalid_argument("FitHeadingDrift: window_steps < 1");
  const std::vector<Window> windows = Windows(odometry, estimate, params.window_steps);
  if (windows.empty()) {
    throw std::invalid_argument("FitHeadingDrift: fewer steps than one window (" +
                                std::to_string(params.window_steps) + ")");
  }
  double dd = 0.0, de = 0.0;
  for (const Window& w : windows) {
    dd += w.distance_m * w.distance_m;
    de += w.distance_m * w.disagreement_rad;
  }
  HeadingDriftFit fit;
  fit.windows = static_cast<int>(windows.size());
  fit.drift_rad_per_m = dd > 0.0 ? de / dd : 0.0;
  double before = 0.0, after = 0.0;
  for (const Window& w : windows) {
    const double left = w.disagreement_rad - fit.drift_rad_per_m * w.distance_m;
    before += w.disagreement_rad * w.disagreement_rad;
    after += left * left;
  }
  fit.rms_before_rad = std::sqrt(before / fit.windows);
  fit.rms_after_rad = std::sqrt(after / fit.windows);
  return fit;
}

}  // namespace slamkit
