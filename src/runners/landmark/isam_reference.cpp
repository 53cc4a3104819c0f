#include <cmath>
#include <vector>

#include "isam_steps.hpp"
#include "slamkit/eval/landmark_smoother.hpp"
#include "slamkit/runners/landmark/isam_run.hpp"

namespace slamkit {
namespace {

void AddSightings(int pose, const std::vector<PointObservation>& sightings,
                  const IsamRunParams& params, std::vector<SmootherSighting>& out) {
  for (const PointObservation& s : sightings) {
    out.push_back({pose, s.id, s.z, isam_detail::SightingCovariance(s, params)});
  }
}

}  // namespace

IsamSmoothedReference SmoothIsamLog(const IsamLog& log, const IsamRunParams& params) {
  IsamRunParams known = params;
  known.ekf.association_method = AssociationMethod::kKnown;
  known.score_against_merged_reference = false;
  known.compare_with_smoothed_reference = false;
  const IsamRunResult start = RunEkfSlamOnIsam(log, known);
  std::vector<Pose2> poses;
  poses.reserve(start.estimate.size());
  for (const StampedPose& p : start.estimate) poses.push_back(p.pose);
  std::vector<SmootherOdometry> odometry;
  std::vector<SmootherSighting> sightings;
  AddSightings(0, log.initial_sightings, params, sightings);
  for (std::size_t k = 0; k < log.steps.size(); ++k) {
    const IsamStep& step = log.steps[k];
    const Control u = isam_detail::StepControl(step, params);
    const int from = static_cast<int>(k), to = from + 1;
    odometry.push_back({from, to, Pose2(u(0), u(1), u(2)),
                        isam_detail::StepCovariance(step, params)});
    AddSightings(to, step.sightings, params, sightings);
  }
  const LandmarkSmootherResult smoothed = SmoothLandmarkSlam(poses, odometry, sightings);
  IsamSmoothedReference out;
  for (std::size_t k = 0; k < smoothed.poses.size(); ++k) {
    out.path.push_back({start.estimate[k].t_s, smoothed.poses[k]});
  }
  out.landmarks = smoothed.landmarks;
  return out;
}

}  // namespace slamkit
