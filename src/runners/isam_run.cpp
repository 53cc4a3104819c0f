#include "slamkit/runners/isam_run.hpp"

#include <chrono>
#include <algorithm>
#include <map>
#include <set>

#include "slamkit/models/odometry.hpp"
#include "slamkit/models/relative_point.hpp"

namespace slamkit {
namespace {

// One-to-one matching of our landmarks to the file's ids, greedily by the number of sightings
// they share (largest first); the agreement is the share of all sightings that fall on matched
// pairs. A file landmark split into two of ours, or two merged into one, loses the smaller part.
double AssociationAgreement(const std::vector<std::pair<int, LandmarkId>>& assigned,
                            int sightings) {
  std::map<std::pair<int, LandmarkId>, int> shared;
  for (const auto& pair : assigned) {
    if (pair.first >= 0) ++shared[pair];
  }
  std::vector<std::pair<int, std::pair<int, LandmarkId>>> by_count;
  for (const auto& [pair, count] : shared) by_count.push_back({count, pair});
  std::stable_sort(by_count.begin(), by_count.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::set<int> ours_taken;
  std::set<LandmarkId> theirs_taken;
  int agree = 0;
  for (const auto& [count, pair] : by_count) {
    if (ours_taken.count(pair.first) || theirs_taken.count(pair.second)) continue;
    ours_taken.insert(pair.first);
    theirs_taken.insert(pair.second);
    agree += count;
  }
  return sightings > 0 ? double(agree) / double(sightings) : 1.0;
}

}  // namespace

IsamRunResult RunEkfSlamOnIsam(const IsamLog& log, const IsamRunParams& params) {
  const auto start = std::chrono::steady_clock::now();
  EkfSlam slam(params.ekf, std::make_unique<OdometryModel>(),
               std::make_unique<RelativePointModel>());
  slam.Reset(Pose2());
  IsamRunResult out;
  std::vector<std::pair<int, LandmarkId>> assigned;
  auto update = [&](const std::vector<PointObservation>& sightings) {
    std::vector<PointObservation> input = sightings;
    for (PointObservation& s : input) {
      s.R *= params.sighting_covariance_scale;
      if (!params.ekf.known_association()) s.id = kNoLandmark;  // ids only score the result
    }
    const auto decisions = slam.Update(input);
    for (std::size_t i = 0; i < decisions.size(); ++i) {
      out.dropped += decisions[i].kind == AssociationDecision::Kind::kDropped ? 1 : 0;
      assigned.emplace_back(decisions[i].landmark, sightings[i].id);
    }
    out.sightings += static_cast<int>(sightings.size());
  };
  update(log.initial_sightings);
  out.estimate.push_back({double(log.initial_pose_index), slam.pose()});
  for (const IsamStep& step : log.steps) {
    const ControlCovariance q = step.odometry_covariance * params.odometry_covariance_scale;
    slam.Predict(Control(step.odometry), 0.0, &q);
    update(step.sightings);
    out.estimate.push_back({double(step.pose_index), slam.pose()});
  }
  // Before anything is taken from the state: a run gone numerically bad gives no map of NaN.
  slam.CheckOutputHealth();
  out.map = slam.Map();
  out.association_agreement = AssociationAgreement(assigned, out.sightings);
  out.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace slamkit
