#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include "fastslam_steps.hpp"
#include "slamkit/core/angle.hpp"
#include "slamkit/filters/ekf/kalman_update.hpp"
#include "slamkit/models/motion_sampling.hpp"

namespace slamkit::fastslam_detail {
namespace {

// The particle's pose belief during a scan: a point for FastSLAM 1.0, a Gaussian refined by each
// matched sighting for 2.0.
struct PoseBelief {
  Pose2 mean;
  Eigen::Matrix3d covariance;
};

// A sighting compared with one landmark: innovation, its covariance with the pose and landmark
// uncertainty, and the Jacobians the proposal needs.
struct Comparison {
  Eigen::Vector2d nu;
  Eigen::Matrix2d Q;  // R + H_m P H_mᵀ (Montemerlo et al. 2003, Eq. 12)
  Eigen::Matrix2d L;  // Q + H_x Σ H_xᵀ (Montemerlo et al. 2003, Eq. 21)
  Eigen::Matrix<double, 2, 3> H_x;
  double log_likelihood = -kInfinity;
  double distance_chi2 = kInfinity;
};

struct Match {
  int candidate = -1;  // -1: a new landmark (or dropped with `dropped`)
  bool dropped = false;
  Comparison comparison;
  double nearest_chi2 = kInfinity;
};

Comparison Compare(const Candidate& c, const PoseBelief& x, const PointObservation& obs,
                   const PointSensorModel& sensor) {
  Comparison out;
  Eigen::Matrix2d H_m;
  const Eigen::Vector2d z_pred = sensor.Predict(x.mean, c.landmark.mean, &out.H_x, &H_m);
  out.nu = sensor.Innovation(obs.z, z_pred);
  out.Q = H_m * c.landmark.covariance * H_m.transpose() + obs.R;
  out.L = out.Q + out.H_x * x.covariance * out.H_x.transpose();
  const Eigen::LLT<Eigen::Matrix2d> llt(out.L);
  if (llt.info() != Eigen::Success) return out;
  out.distance_chi2 = out.nu.dot(llt.solve(out.nu));
  out.log_likelihood = LogGaussianDensity(out.distance_chi2, out.L);
  return out;
}

// The candidate of `slot` (loaded from the tree if the grid did not bring it), or -1.
int FindOrLoad(std::vector<Candidate>& candidates, const FastSlamParticle& p, int slot) {
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].slot == slot) return static_cast<int>(i);
  }
  const FastSlamLandmark* l = p.landmarks.Get(slot);
  if (l == nullptr) return -1;
  candidates.push_back({slot, *l});
  return static_cast<int>(candidates.size()) - 1;
}

// Known association: the observation's id names the slot; a second sighting of it in one scan
// is dropped, as KnownAssociation takes a landmark once per scan.
Match KnownMatch(std::vector<Candidate>& candidates, const FastSlamParticle& p,
                 const PoseBelief& x, const PointObservation& obs, const ScanInputs& scan) {
  Match m;
  const auto it = obs.id == kNoLandmark ? scan.slot_of_id.end() : scan.slot_of_id.find(obs.id);
  if (it == scan.slot_of_id.end()) return m;
  m.candidate = FindOrLoad(candidates, p, it->second);
  if (m.candidate < 0) return m;
  m.dropped = candidates[m.candidate].taken;
  m.comparison = Compare(candidates[m.candidate], x, obs, scan.sensor);
  m.nearest_chi2 = m.comparison.distance_chi2;
  if (m.dropped) m.candidate = -1;
  return m;
}

// Montemerlo et al. 2003, Sec. 4 (and 2002, Sec. 4.4): the most likely landmark not yet taken in
// this scan, or a new landmark when even that one is less likely than p0.
Match MostLikely(const std::vector<Candidate>& candidates, const PoseBelief& x,
                 const PointObservation& obs, const ScanInputs& scan) {
  Match m;
  double best = LogNewLandmarkLikelihood(obs.R, scan.params.new_landmark_chi2);
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].taken) continue;
    Comparison c = Compare(candidates[i], x, obs, scan.sensor);
    m.nearest_chi2 = std::min(m.nearest_chi2, c.distance_chi2);
    if (c.log_likelihood > best) {
      best = c.log_likelihood;
      m.candidate = static_cast<int>(i);
      m.comparison = c;
    }
  }
  return m;
}

// The EKF's rule per particle (SPEC S2, Eqs. 6-7): the most likely landmark not yet taken among
// those within gate_chi2; none there but one within new_landmark_chi2: dropped as ambiguous;
// none within that either: new. p0 compares a density with densities of other covariances, so
// a landmark whose prediction is uncertain (2.0's pose covariance after a long blind stretch)
// loses to p0 even when it lies well within its distribution; the distance does not.
Match WithinGates(const std::vector<Candidate>& candidates, const PoseBelief& x,
                  const PointObservation& obs, const ScanInputs& scan) {
  Match m;
  double best = -kInfinity;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i].taken) continue;
    Comparison c = Compare(candidates[i], x, obs, scan.sensor);
    m.nearest_chi2 = std::min(m.nearest_chi2, c.distance_chi2);
    if (c.distance_chi2 <= scan.params.gate_chi2 && c.log_likelihood > best) {
      best = c.log_likelihood;
      m.candidate = static_cast<int>(i);
      m.comparison = c;
    }
  }
  m.dropped = m.candidate < 0 && m.nearest_chi2 <= scan.params.new_landmark_chi2;
  return m;
}

Match Decide(std::vector<Candidate>& candidates, const FastSlamParticle& p, const PoseBelief& x,
             const PointObservation& obs, const ScanInputs& scan) {
  if (scan.params.known_association) return KnownMatch(candidates, p, x, obs, scan);
  if (scan.params.new_landmark_test == NewLandmarkTest::kMahalanobis) {
    return WithinGates(candidates, x, obs, scan);
  }
  return MostLikely(candidates, x, obs, scan);
}

// Montemerlo et al. 2003, Eqs. 19-20 in Kalman form: the pose proposal conditioned on one more
// sighting of a known landmark, whose uncertainty enters through Q. The Kalman form needs no
// inverse of Σ, which is singular for a motion model with fewer noise components than states.
void RefineProposal(PoseBelief& x, const Comparison& c) {
  const KalmanCorrection<3, 2> k =
      KalmanUpdate<3, 2>(x.mean.vector(), x.covariance, c.nu, c.H_x, c.Q);
  if (!k.ok) return;
  x.mean = Pose2(k.mean);
  x.covariance = k.covariance;
}

Pose2 SampleProposal(const PoseBelief& x, Rng& rng) {
  if (x.covariance.isZero(0.0)) return x.mean;
  const Eigen::VectorXd d = rng.MultivariateNormal(x.covariance);
  return Pose2(x.mean.vector() + Eigen::Vector3d(d));
}

// SPEC S2, Eq. 8 per particle: the new landmark by the inverse model, its covariance J R Jᵀ.
FastSlamLandmark InitialiseLandmark(const Pose2& x, const PointObservation& obs,
                                    const PointSensorModel& sensor) {
  Eigen::Matrix2d J_l_z;
  FastSlamLandmark l;
  l.mean = sensor.Invert(x, obs.z, nullptr, &J_l_z);
  l.covariance = J_l_z * obs.R * J_l_z.transpose();
  return l;
}

// Montemerlo et al. 2002, Sec. 4.3: landmarks in view that no sighting matched lose a count.
void ApplyNegativeEvidence(std::vector<Candidate>& candidates, const Pose2& x,
                           const ScanInputs& scan) {
  const double range_m = scan.sensor.MaxRange() - scan.params.negative_evidence_margin_m;
  for (Candidate& c : candidates) {
    if (c.taken) continue;
    const Eigen::Vector2d local = x.TransformTo(c.landmark.mean);
    const double bearing = std::atan2(local.y(), local.x());
    if (local.norm() > range_m ||
        std::abs(bearing) > 0.5 * scan.params.negative_evidence_fov_rad) {
      continue;
    }
    --c.landmark.evidence;
    c.changed = true;
  }
}

AssociationDecision DecisionOf(const Match& m, const std::vector<Candidate>& candidates) {
  AssociationDecision d;
  d.distance_chi2 = m.nearest_chi2;
  if (m.dropped) return d;
  if (m.candidate < 0) {
    d.kind = AssociationDecision::Kind::kNew;
    return d;
  }
  d.kind = AssociationDecision::Kind::kMatched;
  d.landmark = candidates[m.candidate].slot;
  d.distance_chi2 = m.comparison.distance_chi2;
  return d;
}

// Decides every sighting of the scan in order and accumulates the weight: the likelihood of a
// matched sighting under L (Montemerlo et al. 2003, Eq. 21; with Σ = 0 that of FastSLAM 1.0,
// Montemerlo et al. 2002, Eq. 9), or p0 for a new landmark. 2.0 refines the pose proposal with
// each match, so later sightings are compared from the refined pose.
std::vector<Match> Associate(std::vector<Candidate>& candidates, const FastSlamParticle& p,
                             PoseBelief& x, const ScanInputs& scan, double& log_weight) {
  std::vector<Match> matches;
  matches.reserve(scan.observations.size());
  for (const PointObservation& obs : scan.observations) {
    Match m = Decide(candidates, p, x, obs, scan);
    if (m.candidate >= 0) {
      candidates[m.candidate].taken = true;
      log_weight += m.comparison.log_likelihood;
      if (scan.params.proposal == FastSlamProposal::kObservation) RefineProposal(x, m.comparison);
    } else if (!m.dropped || !scan.params.known_association) {
      // A sighting left unmatched has p0 (dropped ones too: a particle that cannot tell must not
      // gain on one that matched, by a density of 1 against one of other units).
      log_weight += LogNewLandmarkLikelihood(obs.R, scan.params.new_landmark_chi2);
    }
    matches.push_back(m);
  }
  return matches;
}

}  // namespace

// Montemerlo et al. 2003, Sec. 4: the likelihood p0 a sighting must beat to be matched, here the
// density of N(0, R) at squared Mahalanobis distance `chi2`, so it scales with the sensor.
double LogGaussianDensity(double chi2, const Eigen::Matrix2d& S) {
  return -0.5 * chi2 - std::log(2.0 * std::numbers::pi) - 0.5 * std::log(S.determinant());
}

double LogNewLandmarkLikelihood(const Eigen::Matrix2d& R, double chi2) {
  return LogGaussianDensity(chi2, R);
}

std::vector<Candidate> GatherCandidates(const FastSlamParticle& p, const ScanInputs& scan) {
  const double radius_m = scan.sensor.MaxRange() + scan.params.association_margin_m;
  std::vector<int> slots;
  SlotsNear(scan.grid, p.pose.translation(), radius_m, scan.params.index_cell_m, slots);
  std::vector<Candidate> out;
  for (int slot : slots) {
    const FastSlamLandmark* l = p.landmarks.Get(slot);
    if (l != nullptr && (l->mean - p.pose.translation()).norm() <= radius_m) {
      out.push_back({slot, *l});
    }
  }
  return out;
}

// Montemerlo et al. 2002, Eqs. 4-6: the landmark's EKF update with the sighting, from the pose
// the particle now holds.
void UpdateLandmark(Candidate& c, const Pose2& x, const PointObservation& obs,
                    const PointSensorModel& sensor) {
  Eigen::Matrix2d H_m;
  const Eigen::Vector2d z_pred = sensor.Predict(x, c.landmark.mean, nullptr, &H_m);
  const KalmanCorrection<2, 2> k = KalmanUpdate<2, 2>(
      c.landmark.mean, c.landmark.covariance, sensor.Innovation(obs.z, z_pred), H_m, obs.R);
  if (!k.ok) return;
  c.landmark.mean = k.mean;
  c.landmark.covariance = k.covariance;
  ++c.landmark.evidence;
  c.changed = true;
}

void WriteBack(FastSlamParticle& p, const std::vector<Candidate>& candidates) {
  for (const Candidate& c : candidates) {
    if (!c.changed) continue;
    if (c.landmark.evidence <= 0) {
      p.landmarks.Erase(c.slot);
    } else {
      p.landmarks.Set(c.slot, c.landmark);
    }
  }
}

void PredictParticle(FastSlamParticle& p, const MotionModel& motion, FastSlamProposal proposal,
                     const Control& u, double dt_s, const ControlCovariance& Q, Rng& rng) {
  if (proposal == FastSlamProposal::kMotion) {
    // Montemerlo et al. 2002, Eq. 3 (Probabilistic Robotics Table 5.3): a motion sample.
    p.pose = SampleMotion(motion, p.pose, u, dt_s, rng, &Q);
    return;
  }
  // Montemerlo et al. 2003, Sec. 3: 2.0 keeps the predicted pose as a Gaussian, linearised at
  // its mean, and samples only once the scan has conditioned it.
  Eigen::Matrix3d J_x;
  ControlJacobian J_u;
  p.pose = motion.Move(p.pose, u, dt_s, &J_x, &J_u);
  p.pose_covariance =
      J_x * p.pose_covariance * J_x.transpose() + J_u * Q * J_u.transpose();
  if (p.window_covariance.size() > 0) {
    PropagateWindow(p.window_covariance, J_x, J_u * Q * J_u.transpose());
  }
}

void UpdateParticle(FastSlamParticle& p, const ScanInputs& scan, Rng& rng, ParticleUpdate& out) {
  out.created_in_window.assign(scan.observations.size(), -1);
  if (p.window_covariance.size() > 0) {
    UpdateWithWindow(p, scan, rng, out);
    return;
  }
  const bool need_nearby = !scan.params.known_association || scan.params.negative_evidence;
  std::vector<Candidate> candidates =
      need_nearby ? GatherCandidates(p, scan) : std::vector<Candidate>{};
  out.decisions.clear();
  out.log_weight = 0.0;
  PoseBelief x{p.pose, p.pose_covariance};
  const std::vector<Match> matches = Associate(candidates, p, x, scan, out.log_weight);
  p.pose = SampleProposal(x, rng);  // Montemerlo et al. 2003, Eq. 20 (1.0: Σ = 0, kept as is)
  p.pose_covariance.setZero();
  out.created.resize(matches.size());
  for (std::size_t i = 0; i < matches.size(); ++i) {
    const Match& m = matches[i];
    if (m.candidate >= 0) {
      UpdateLandmark(candidates[m.candidate], p.pose, scan.observations[i], scan.sensor);
    } else if (!m.dropped) {
      out.created[i] = InitialiseLandmark(p.pose, scan.observations[i], scan.sensor);
    }
    out.decisions.push_back(DecisionOf(m, candidates));
  }
  if (scan.params.negative_evidence) ApplyNegativeEvidence(candidates, p.pose, scan);
  WriteBack(p, candidates);
}

void InsertCreated(FastSlamParticle& p, const ParticleUpdate& update,
                   const std::vector<int>& slot_of_observation) {
  for (std::size_t i = 0; i < update.decisions.size(); ++i) {
    if (update.decisions[i].kind != AssociationDecision::Kind::kNew) continue;
    const int in_window = i < update.created_in_window.size() ? update.created_in_window[i] : -1;
    if (in_window >= 0) {
      p.window[in_window].slot = slot_of_observation[i];
    } else {
      p.landmarks.Set(slot_of_observation[i], update.created[i]);
    }
  }
}

}  // namespace slamkit::fastslam_detail
