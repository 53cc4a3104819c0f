// SPEC S3: scoring a cooperative run's traces against the fleet's truth.
#include "coop_scoring.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <Eigen/Eigenvalues>

#include "slamkit/core/angle.hpp"
#include "slamkit/eval/alignment.hpp"
#include "slamkit/eval/errors.hpp"

namespace slamkit::internal {
namespace {
constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();
constexpr double kMaxTruthGapS = 0.5;

// CoopVehicleTrace::position_aligned_rmse_m.
double AlignedPositionRmse(const CoopVehicleTrace& trace) {
  if (trace.estimate.size() < 2) return -1.0;
  std::vector<Eigen::Vector2d> estimated, true_positions;
  for (std::size_t k = 0; k < trace.estimate.size(); ++k) {
    estimated.push_back(trace.estimate[k].pose.translation());
    true_positions.push_back(trace.truth[k].pose.translation());
  }
  return AlignPoints(estimated, true_positions).rmse_m;
}

}  // namespace

std::optional<Pose2> TruthAt(const Trajectory& path, double t) {
  const auto after = std::lower_bound(path.begin(), path.end(), t,
                                      [](const StampedPose& s, double time) { return s.t_s < time; });
  const StampedPose* best = nullptr;
  if (after != path.end()) best = &*after;
  if (after != path.begin()) {
    const StampedPose& before = *std::prev(after);
    if (best == nullptr || t - before.t_s < best->t_s - t) best = &before;
  }
  if (best == nullptr || std::abs(best->t_s - t) > kMaxTruthGapS) return std::nullopt;
  return best->pose;
}

bool Record(CoopVehicleTrace& trace, double t, const Pose2& estimate, const Eigen::Matrix3d& cov,
            const Trajectory& truth) {
  const std::optional<Pose2> true_pose = TruthAt(truth, t);
  if (!true_pose) return false;
  trace.estimate.push_back({t, estimate});
  trace.covariance.push_back(cov);
  trace.truth.push_back({t, *true_pose});
  return true;
}

void Summarise(CoopVehicleTrace& trace, const LandmarkWorld& world,
               const std::vector<LandmarkId>& landmark_truth) {
  std::vector<Eigen::Vector3d> errors;
  double nees_sum = 0.0;
  int defined = 0;
  for (std::size_t k = 0; k < trace.estimate.size(); ++k) {
    Eigen::Vector3d e = trace.estimate[k].pose.vector() - trace.truth[k].pose.vector();
    e[2] = WrapAngle(e[2]);
    errors.push_back(e);
    const Eigen::Matrix3d& C = trace.covariance[k];
    // A pose known exactly in some direction (the known start, dead reckoning) has no NEES.
    const Eigen::Vector3d eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(C).eigenvalues();
    const bool definite = eigenvalues.minCoeff() > 1e-12 * eigenvalues.maxCoeff();
    trace.nees.push_back(definite ? Nees(e, C) : kNoValue);
    if (definite) {
      nees_sum += trace.nees.back();
      ++defined;
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(C.topLeftCorner<2, 2>());
    trace.position_cov_norm.push_back(eig.eigenvalues().maxCoeff());
  }
  const PoseRmse rmse = ComputePoseRmse(errors);
  trace.position_rmse_m = rmse.position_m;
  trace.heading_rmse_rad = rmse.heading_rad;
  trace.position_aligned_rmse_m = AlignedPositionRmse(trace);
  trace.mean_nees = defined > 0 ? nees_sum / defined : kNoValue;
  std::unordered_map<LandmarkId, Eigen::Vector2d> truth;
  for (const Landmark& l : world.landmarks) truth.emplace(l.id, l.position_m);
  std::vector<Eigen::Vector2d> from, to;
  for (std::size_t i = 0; i < trace.map.landmarks.size() && i < landmark_truth.size(); ++i) {
    const auto it = truth.find(landmark_truth[i]);
    if (it == truth.end()) continue;
    from.push_back(trace.map.landmarks[i].position_m);
    to.push_back(it->second);
  }
  if (from.size() >= 2) trace.map_rmse_m = AlignPoints(from, to).rmse_m;
}

CoopModeResult DeadReckoning(const FleetLog& log, const FleetTruth& truth,
                             const CoopFilterParams& p) {
  CoopModeResult out;
  out.mode = CoopMode::kDeadReckoning;
  out.vehicles.resize(log.vehicles);
  const UnicycleModel model(p.motion);
  std::vector<Pose2> pose = log.start_poses;
  std::vector<double> last(log.vehicles, -1e300);
  for (const FleetEvent& e : log.events) {
    if (e.kind != FleetEvent::Kind::kControl) continue;
    CoopVehicleTrace& trace = out.vehicles[e.vehicle];
    if (e.t_s - last[e.vehicle] >= p.record_period_s &&
        Record(trace, e.t_s, pose[e.vehicle], Eigen::Matrix3d::Zero(), truth.paths[e.vehicle])) {
      last[e.vehicle] = e.t_s;
    }
    Control u(2);
    u << e.value.x(), e.value.y();
    pose[e.vehicle] = model.Move(pose[e.vehicle], u, e.dt_s);
  }
  for (CoopVehicleTrace& trace : out.vehicles) Summarise(trace, truth.world, {});
  return out;
}

}  // namespace slamkit::internal

namespace slamkit {

std::vector<double> ImprovementRatio(const std::vector<double>& mono_t_s,
                                     const std::vector<double>& mono_norm,
                                     const std::vector<double>& t_s,
                                     const std::vector<double>& norm) {
  std::vector<double> ir;
  std::size_t j = 0;  // Mono's latest record at or before t_s[k]
  for (std::size_t k = 0; k < std::min(t_s.size(), norm.size()); ++k) {
    while (j + 1 < mono_t_s.size() && mono_t_s[j + 1] <= t_s[k]) ++j;
    if (mono_t_s.empty() || mono_t_s[j] > t_s[k] || j >= mono_norm.size()) continue;
    const double m = mono_norm[j];
    ir.push_back(m > 0.0 ? 100.0 * (m - norm[k]) / m : 0.0);
  }
  return ir;
}

std::vector<double> ImprovementRatio(const CoopVehicleTrace& mono, const CoopVehicleTrace& other) {
  const auto times = [](const Trajectory& path) {
    std::vector<double> t;
    for (const StampedPose& p : path) t.push_back(p.t_s);
    return t;
  };
  return ImprovementRatio(times(mono.estimate), mono.position_cov_norm, times(other.estimate),
                          other.position_cov_norm);
}

}  // namespace slamkit
