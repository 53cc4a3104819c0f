#include "slamkit/runners/landmark/filter_choice.hpp"

#include <stdexcept>
#include <string>

#include "slamkit/io/error.hpp"

namespace slamkit {

FilterKind ParseFilterKind(std::string_view name) {
  for (FilterKind kind : {FilterKind::kEkf, FilterKind::kFastSlam1, FilterKind::kFastSlam2}) {
    if (name == FilterName(kind)) return kind;
  }
  throw InputError("unknown filter '" + std::string(name) +
                   "': expected ekf, fastslam1 or fastslam2");
}

std::string_view FilterName(FilterKind kind) {
  switch (kind) {
    case FilterKind::kEkf: return "ekf";
    case FilterKind::kFastSlam1: return "fastslam1";
    case FilterKind::kFastSlam2: return "fastslam2";
  }
  return "?";
}

std::string_view FilterTitle(FilterKind kind) {
  switch (kind) {
    case FilterKind::kEkf: return "EKF-SLAM";
    case FilterKind::kFastSlam1: return "FastSLAM 1.0";
    case FilterKind::kFastSlam2: return "FastSLAM 2.0";
  }
  return "?";
}

FastSlamParams FastSlamParamsFor(FilterKind kind, int particles, const EkfSlamParams& ekf) {
  if (kind == FilterKind::kEkf) throw std::invalid_argument("FastSlamParamsFor: not FastSLAM");
  FastSlamParams fastslam;
  fastslam.proposal =
      kind == FilterKind::kFastSlam1 ? FastSlamProposal::kMotion : FastSlamProposal::kObservation;
  fastslam.particles = particles;
  fastslam.known_association = ekf.known_association();
  fastslam.new_landmark_chi2 = ekf.association.new_landmark_chi2;
  fastslam.gate_chi2 = ekf.association.gate_chi2;
  fastslam.association_margin_m = ekf.association_margin_m;
  return fastslam;
}

LandmarkFilterFactory FactoryForFilter(FilterKind kind, int particles,
                                       const ScenarioConfig& config) {
  if (kind == FilterKind::kEkf) return EkfSlamFactory(config);
  if (particles < 1) {
    throw InputError("FastSLAM needs at least one particle, not " + std::to_string(particles));
  }
  FastSlamParams fastslam = FastSlamParamsFor(kind, particles, config.ekf);
  // Delayed sampling needs each particle's own association (FastSlam throws otherwise).
  fastslam.delayed_sampling = config.fastslam.delayed_sampling && !fastslam.known_association;
  fastslam.window_max_landmarks = config.fastslam.window_max_landmarks;
  return FastSlamFactory(fastslam, config.scenario.vehicle, config.scenario.sensor);
}

LandmarkFilterFactory FactoryForFilter(std::string_view name, int particles,
                                       const ScenarioConfig& config) {
  return FactoryForFilter(ParseFilterKind(name), particles, config);
}

}  // namespace slamkit
