// The "mono-smoothed" mode: what one vehicle's own data allow, as a batch estimate.
#include "coop_smoothed.hpp"

#include <algorithm>
#include <span>

#include "coop_lag.hpp"
#include "slamkit/eval/landmark_smoother.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/unicycle.hpp"

namespace slamkit::internal {
namespace {

// Added to every step's covariance (m², m², rad²): the unicycle's noise has none sideways, and
// a step standing still (no control yet) none at all, which the smoother cannot invert. Steps
// nearly that rigid slow Levenberg-Marquardt down (MRCLAM Dataset 6: at 10⁻¹² 13 of 14 solves
// stopped at 100 iterations); 10⁻⁶ (1 mm, 1 mrad a step) converges in about 30, and 10⁻⁷ or
// 10⁻⁸ moved the robots' mean error by 0.002 m (docs/cooperative.md).
constexpr double kStepFloorVariance = 1e-6;

// The smoother's problem, built node by node while walking the vehicle's events.
class ProblemBuilder {
 public:
  ProblemBuilder(const CoopFilterParams& params, const Trajectory& start, double t0,
                 const Pose2& start_pose)
      : params_(params), model_(params.motion), start_(start) {
    times_.push_back(t0);
    poses_.push_back(start_pose);
  }

  // Composes the held control from the last integrated time to t onto the open step.
  void MoveTo(double t) {
    if (t > step_.t_s && control_.size() > 0)
      Step(model_, params_, control_, t - step_.t_s, &step_);
    step_.t_s = std::max(step_.t_s, t);
  }

  // Closes the open step with a node at t (MoveTo(t) first).
  void NodeAt(double t) {
    if (t <= times_.back()) return;
    MoveTo(t);
    const int from = static_cast<int>(times_.size()) - 1;
    odometry_.push_back({from, from + 1, step_.pose,
                         step_.covariance + kStepFloorVariance * Eigen::Matrix3d::Identity()});
    times_.push_back(t);
    poses_.push_back(StartAt(t));
    step_ = PoseNow{t, Pose2(), Eigen::Matrix3d::Zero()};
  }

  void SetControl(double t, const Eigen::Vector2d& u) {
    MoveTo(t);
    control_ = Control(2);
    control_ << u.x(), u.y();
  }

  // The sighting as a point in the vehicle's frame, its covariance carried through the
  // range-bearing model's inverse.
  void AddSighting(LandmarkId id, const Eigen::Vector2d& range_bearing, const Eigen::Matrix2d& R) {
    Eigen::Matrix2d J;
    const Eigen::Vector2d point =
        InvertRangeBearing(Pose2(), {range_bearing.x(), range_bearing.y()}, nullptr, &J);
    sightings_.push_back({static_cast<int>(times_.size()) - 1, id, point, J * R * J.transpose()});
  }

  double last_node_s() const { return times_.back(); }
  const std::vector<double>& times() const { return times_; }
  const std::vector<Pose2>& poses() const { return poses_; }
  const std::vector<SmootherOdometry>& odometry() const { return odometry_; }
  std::vector<SmootherSighting>& sightings() { return sightings_; }

 private:
  // The filtered pose at or before t (the first one before the path starts).
  Pose2 StartAt(double t) const {
    const auto after =
        std::upper_bound(start_.begin(), start_.end(), t,
                         [](double time, const StampedPose& s) { return time < s.t_s; });
    return after == start_.begin() ? poses_.back() : std::prev(after)->pose;
  }

  const CoopFilterParams& params_;
  const UnicycleModel model_;
  const Trajectory& start_;
  std::vector<double> times_;
  std::vector<Pose2> poses_;
  std::vector<SmootherOdometry> odometry_;
  std::vector<SmootherSighting> sightings_;
  Control control_;
  PoseNow step_{-1e300, Pose2(), Eigen::Matrix3d::Zero()};  // the motion since the last node
};

// The sightings within `gate_chi2` of their landmark at `solution`.
std::vector<SmootherSighting> WithinGate(std::span<const SmootherSighting> sightings,
                                         const LandmarkSmootherResult& solution, double gate_chi2) {
  std::vector<SmootherSighting> kept;
  for (const SmootherSighting& s : sightings) {
    const Eigen::Vector2d e =
        s.z - solution.poses[s.pose].TransformTo(solution.landmarks.at(s.landmark));
    if (e.dot(s.covariance.ldlt().solve(e)) <= gate_chi2) kept.push_back(s);
  }
  return kept;
}

}  // namespace

MonoSmoothing SmoothMonoVehicle(const FleetLog& log, const std::vector<LandmarkId>& true_ids,
                                int vehicle, const Trajectory& start,
                                const CoopFilterParams& params, double node_period_s) {
  const double t0 = log.events.empty() ? 0.0 : log.events.front().t_s;
  ProblemBuilder builder(params, start, t0, log.start_poses.at(vehicle));
  builder.MoveTo(t0);
  const Eigen::Matrix2d R = RangeBearingModel(params.sensor).NoiseCovariance();
  for (std::size_t i = 0; i < log.events.size(); ++i) {
    const FleetEvent& e = log.events[i];
    if (e.vehicle != vehicle || e.kind == FleetEvent::Kind::kVehicleSighting) continue;
    if (e.kind == FleetEvent::Kind::kControl) {
      if (e.t_s - builder.last_node_s() >= node_period_s) builder.NodeAt(e.t_s);
      builder.SetControl(e.t_s, e.value);
      continue;
    }
    const LandmarkId id = true_ids.empty() ? e.landmark : true_ids[i];
    if (id == kNoLandmark) continue;
    builder.NodeAt(e.t_s);
    builder.AddSighting(id, e.value, R);
  }
  LandmarkSmootherParams smoother;
  smoother.max_iterations = 200;
  std::vector<SmootherSighting>& sightings = builder.sightings();
  const int all = static_cast<int>(sightings.size());
  LandmarkSmootherResult solution;
  for (int round = 0;; ++round) {
    solution = SmoothLandmarkSlam(builder.poses(), builder.odometry(), sightings, smoother);
    if (round == 2) break;
    std::vector<SmootherSighting> kept = WithinGate(sightings, solution, params.known_gate_chi2);
    if (kept.size() == sightings.size()) break;
    sightings = std::move(kept);
  }
  MonoSmoothing out;
  for (std::size_t k = 0; k < solution.poses.size(); ++k) {
    out.path.push_back({builder.times()[k], solution.poses[k]});
  }
  for (const auto& [id, position] : solution.landmarks) {
    out.map.landmarks.push_back({id, position, Eigen::Matrix2d::Zero()});
    out.landmark_truth.push_back(id);
  }
  out.sightings_used = static_cast<int>(sightings.size());
  out.sightings_dropped = all - out.sightings_used;
  return out;
}

}  // namespace slamkit::internal
