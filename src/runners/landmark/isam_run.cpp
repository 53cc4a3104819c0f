#include "slamkit/runners/landmark/isam_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "isam_steps.hpp"
#include "slamkit/eval/alignment.hpp"
#include "slamkit/eval/errors.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"
#include "slamkit/models/relative_point.hpp"

namespace slamkit {
namespace {

std::optional<HeadingDriftFit> FitFileOdometry(const IsamLog& log, const Trajectory& estimate,
                                               const HeadingDriftParams& params) {
  if (log.steps.size() < static_cast<std::size_t>(std::max(params.window_steps, 1))) {
    return std::nullopt;
  }
  std::vector<Pose2> odometry;
  odometry.reserve(log.steps.size());
  for (const IsamStep& step : log.steps) {
    odometry.emplace_back(step.odometry.x(), step.odometry.y(), step.odometry.z());
  }
  return FitHeadingDrift(odometry, estimate, params);
}

// Snapshots of the map a run keeps for the replay viewer (`slamkit report`), evenly over its
// steps: enough to watch the map grow, a few MB on Victoria Park.
constexpr std::size_t kMapSnapshots = 50;

// One filter run over the log, with each decision paired with the file's id of its sighting.
struct Pass {
  std::vector<std::pair<int, LandmarkId>> assigned;
  Trajectory estimate;
  std::vector<Eigen::Matrix3d> pose_covariance;  // after each step
  std::vector<LandmarkMapSnapshot> map_history;
  int sightings = 0;
  int outside_gate = 0;  // new landmarks and dropped sightings
  int dropped = 0;
};

Pass RunPass(LandmarkSlamFilter& slam, const IsamLog& log, const IsamRunParams& params,
             bool known_association) {
  Pass pass;
  slam.Reset(Pose2(), Eigen::Matrix3d::Zero());
  auto update = [&](const std::vector<PointObservation>& sightings) {
    std::vector<PointObservation> input = sightings;
    for (PointObservation& s : input) {
      s.R = isam_detail::SightingCovariance(s, params);
      if (!known_association) s.id = kNoLandmark;  // ids only score the result
    }
    const auto decisions = slam.Update(input);
    for (std::size_t i = 0; i < decisions.size(); ++i) {
      pass.dropped += decisions[i].kind == AssociationDecision::Kind::kDropped ? 1 : 0;
      pass.outside_gate += decisions[i].kind != AssociationDecision::Kind::kMatched ? 1 : 0;
      pass.assigned.emplace_back(decisions[i].landmark, sightings[i].id);
    }
    pass.sightings += static_cast<int>(sightings.size());
  };
  update(log.initial_sightings);
  pass.estimate.push_back({double(log.initial_pose_index), slam.PoseEstimate()});
  pass.map_history.push_back({pass.estimate.back().t_s, slam.Map()});
  const std::size_t every = (log.steps.size() + kMapSnapshots - 1) / kMapSnapshots;
  for (const IsamStep& step : log.steps) {
    const ControlCovariance q = isam_detail::StepCovariance(step, params);
    slam.Predict(isam_detail::StepControl(step, params), 0.0, &q);
    update(step.sightings);
    pass.estimate.push_back({double(step.pose_index), slam.PoseEstimate()});
    pass.pose_covariance.push_back(slam.PoseCovariance());
    if ((pass.estimate.size() - 1) % every == 0) {
      pass.map_history.push_back({pass.estimate.back().t_s, slam.Map()});
    }
  }
  // Before anything is taken from the state: a run gone numerically bad gives no map of NaN.
  slam.Flush();
  slam.CheckOutputHealth();
  return pass;
}

IsamReferenceErrors CompareWithReference(const IsamRunResult& run,
                                         const std::map<int, LandmarkId>& pairs,
                                         const IsamSmoothedReference& reference) {
  IsamReferenceErrors out;
  out.ate = AbsoluteTrajectoryError(run.estimate, reference.path);
  std::vector<Eigen::Vector2d> ours, theirs;
  for (const auto& [index, id] : pairs) {
    const auto it = reference.landmarks.find(id);
    if (index >= static_cast<int>(run.map.landmarks.size()) || it == reference.landmarks.end()) {
      continue;
    }
    ours.push_back(run.map.landmarks[index].position_m);
    theirs.push_back(it->second);
  }
  out.landmarks_compared = static_cast<int>(ours.size());
  if (ours.size() >= 2) out.map_rmse_m = AlignPoints(ours, theirs).rmse_m;
  return out;
}

// The pairs of file ids sighted from one pose: two distinct landmarks by the file's own account.
std::set<std::pair<LandmarkId, LandmarkId>> SightedTogether(const IsamLog& log) {
  std::set<std::pair<LandmarkId, LandmarkId>> together;
  auto add = [&](const std::vector<PointObservation>& sightings) {
    for (const PointObservation& a : sightings) {
      for (const PointObservation& b : sightings) {
        if (a.id < b.id) together.insert({a.id, b.id});
      }
    }
  };
  add(log.initial_sightings);
  for (const IsamStep& step : log.steps) add(step.sightings);
  return together;
}

// How many landmarks the file names.
long DistinctIds(const IsamLog& log) {
  std::set<LandmarkId> ids;
  for (const PointObservation& s : log.initial_sightings) ids.insert(s.id);
  for (const IsamStep& step : log.steps) {
    for (const PointObservation& s : step.sightings) ids.insert(s.id);
  }
  return static_cast<long>(ids.size());
}

// Representative of `id` in a union-find forest over file ids.
LandmarkId Root(std::map<LandmarkId, LandmarkId>& parent, LandmarkId id) {
  while (parent.count(id) && parent[id] != id) id = parent[id] = parent[parent[id]];
  return id;
}

}  // namespace

namespace isam_detail {

Eigen::Matrix3d StepCovariance(const IsamStep& step, const IsamRunParams& params) {
  const Pose2 delta(step.odometry.x(), step.odometry.y(), step.odometry.z());
  const Eigen::Vector3d sigmas = OdometryNoiseSigmas(delta, params.odometry_noise);
  return step.odometry_covariance * params.odometry_covariance_scale +
         Eigen::Matrix3d(sigmas.cwiseProduct(sigmas).asDiagonal());
}

Control StepControl(const IsamStep& step, const IsamRunParams& params) {
  Eigen::Vector3d u = step.odometry;
  if (params.odometry_heading_drift_rad_per_m != 0.0) {
    u.z() += params.odometry_heading_drift_rad_per_m * std::hypot(u.x(), u.y());
  }
  return Control(u);
}

Eigen::Matrix2d SightingCovariance(const PointObservation& sighting, const IsamRunParams& params) {
  Eigen::Matrix2d R = sighting.R;
  if (params.sighting_sigma_range_m > 0.0 && params.sighting_sigma_bearing_rad > 0.0) {
    R = RangeBearingCovariance(sighting.z, params.sighting_sigma_range_m,
                               params.sighting_sigma_bearing_rad);
  }
  return R * params.sighting_covariance_scale;
}

}  // namespace isam_detail

std::vector<std::vector<LandmarkId>> IndistinguishableReferenceIds(const IsamLog& log,
                                                                   const IsamRunParams& params) {
  EkfSlamParams known = params.ekf;
  known.association_method = AssociationMethod::kKnown;
  EkfSlam slam(known, std::make_unique<OdometryModel>(), std::make_unique<RelativePointModel>());
  RunPass(slam, log, params, true);
  const auto together = SightedTogether(log);
  std::map<LandmarkId, LandmarkId> parent;
  const int n = slam.NumLandmarks();
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      const Eigen::Vector2d d = slam.LandmarkPosition(a) - slam.LandmarkPosition(b);
      const Eigen::Matrix2d P_ab = slam.LandmarkCovariance(a, b);
      const Eigen::Matrix2d S =
          slam.LandmarkCovariance(a) + slam.LandmarkCovariance(b) - P_ab - P_ab.transpose();
      if (d.dot(S.ldlt().solve(d)) > params.ekf.association.gate_chi2) continue;
      const LandmarkId ia = slam.LandmarkSourceId(a), ib = slam.LandmarkSourceId(b);
      if (together.count({std::min(ia, ib), std::max(ia, ib)})) continue;
      parent.try_emplace(ia, ia);
      parent.try_emplace(ib, ib);
      parent[Root(parent, std::max(ia, ib))] = Root(parent, std::min(ia, ib));
    }
  }
  std::map<LandmarkId, std::vector<LandmarkId>> groups;
  for (const auto& [id, unused] : parent) groups[Root(parent, id)].push_back(id);
  std::vector<std::vector<LandmarkId>> out;
  for (auto& [root, ids] : groups) out.push_back(std::move(ids));
  return out;
}

IsamRunResult RunEkfSlamOnIsam(const IsamLog& log, const IsamRunParams& params) {
  EkfSlam slam(params.ekf, std::make_unique<OdometryModel>(),
               std::make_unique<RelativePointModel>());
  IsamRunResult out = RunFilterOnIsam(slam, log, params, params.ekf.known_association());
  out.innovation_check = CheckInnovations(out.sightings, out.sightings_outside_gate,
                                          DistinctIds(log), 2, params.ekf.association.gate_chi2);
  return out;
}

FastSlamParams IsamFastSlamParams(const IsamRunParams& params, FastSlamParams fastslam) {
  const AssociationParams& ekf = params.ekf.association;
  fastslam.known_association = params.ekf.known_association();
  fastslam.new_landmark_test = params.fastslam.new_landmark_test;
  fastslam.gate_chi2 = params.fastslam.gate_chi2.value_or(ekf.gate_chi2);
  fastslam.new_landmark_chi2 = params.fastslam.new_landmark_chi2.value_or(ekf.new_landmark_chi2);
  // Delayed sampling serves each particle's own association; with the file's ids it is not used.
  fastslam.delayed_sampling = params.fastslam.delayed_sampling && !fastslam.known_association;
  fastslam.window_max_landmarks = params.fastslam.window_max_landmarks;
  return fastslam;
}

IsamRunResult RunFastSlamOnIsam(const IsamLog& log, const IsamRunParams& params,
                                FastSlamParams fastslam) {
  fastslam = IsamFastSlamParams(params, fastslam);
  FastSlam filter(fastslam, std::make_unique<OdometryModel>(),
                  std::make_unique<RelativePointModel>());
  return RunFilterOnIsam(filter, log, params, fastslam.known_association);
}

IsamRunResult RunFilterOnIsam(LandmarkSlamFilter& filter, const IsamLog& log,
                              const IsamRunParams& params, bool known_association) {
  const auto start = std::chrono::steady_clock::now();
  Pass pass = RunPass(filter, log, params, known_association);
  IsamRunResult out;
  out.estimate = std::move(pass.estimate);
  out.pose_covariance = std::move(pass.pose_covariance);
  out.map = filter.Map();
  out.map_history = std::move(pass.map_history);
  if (out.map_history.back().t_s != out.estimate.back().t_s) {
    out.map_history.push_back({out.estimate.back().t_s, out.map});
  }
  out.counters = filter.Counters();
  out.sightings = pass.sightings;
  out.dropped = pass.dropped;
  out.sightings_outside_gate = pass.outside_gate;
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.odometry_heading_drift = FitFileOdometry(log, out.estimate, params.heading_drift_fit);
  const IdAgreement agreement = AssociationAgreement(pass.assigned, out.sightings);
  out.association_agreement = agreement.share;
  if (params.compare_with_smoothed_reference) {
    try {
      out.smoothed_reference =
          CompareWithReference(out, agreement.pairs, SmoothIsamLog(log, params));
    } catch (const std::invalid_argument& e) {
      out.smoothed_reference_failure = e.what();
    }
  }
  if (params.score_against_merged_reference) {
    out.reference_merges = IndistinguishableReferenceIds(log, params);
    std::map<LandmarkId, LandmarkId> merged;
    for (const auto& group : out.reference_merges) {
      for (LandmarkId id : group) merged[id] = group.front();
    }
    for (auto& [ours, theirs] : pass.assigned) {
      if (merged.count(theirs)) theirs = merged[theirs];
    }
    out.association_agreement_merged = AssociationAgreement(pass.assigned, out.sightings).share;
  }
  return out;
}

}  // namespace slamkit
