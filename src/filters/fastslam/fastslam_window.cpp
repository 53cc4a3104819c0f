// FastSLAM 2.0 with delayed sampling (FastSlamParams::delayed_sampling): the particle's pose and
// the landmarks it mapped since its pose was last drawn form one Gaussian, updated as an EKF, and
// the pose is drawn only when a scan matches a landmark of the particle's tree.

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/LU>

#include "fastslam_steps.hpp"

namespace slamkit::fastslam_detail {

void PropagateWindow(Eigen::MatrixXd& P, const Eigen::Matrix3d& J_x,
                     const Eigen::Matrix3d& noise) {
  const int n = static_cast<int>(P.rows());
  P.topLeftCorner<3, 3>() = J_x * P.topLeftCorner<3, 3>() * J_x.transpose() + noise;
  if (n > 3) {
    P.topRightCorner(3, n - 3) = J_x * P.topRightCorner(3, n - 3);
    P.bottomLeftCorner(n - 3, 3) = P.topRightCorner(3, n - 3).transpose();
  }
}

namespace {

// A sighting against a window landmark (`block` ≥ 0) or a landmark of the tree (`tree` set):
// the innovation and its covariance under the window's joint Gaussian.
struct WindowComparison {
  int block = -1;
  int candidate = -1;
  Eigen::Vector2d nu;
  Eigen::Matrix2d S;
  Eigen::Matrix<double, 2, 3> H_x;
  Eigen::Matrix2d H_m;
  double distance_chi2 = kInfinity;
  double log_likelihood = -kInfinity;
};

Eigen::MatrixXd TimesHt(const Eigen::MatrixXd& P, const WindowComparison& c) {
  Eigen::MatrixXd PHt = P.leftCols<3>() * c.H_x.transpose();
  if (c.block >= 0) PHt += P.middleCols(3 + 2 * c.block, 2) * c.H_m.transpose();
  return PHt;
}

WindowComparison CompareWindow(const FastSlamParticle& p, int block, int candidate,
                               const FastSlamLandmark* tree, const PointObservation& obs,
                               const PointSensorModel& sensor) {
  WindowComparison c;
  c.block = block;
  c.candidate = candidate;
  const Eigen::Vector2d& l = block >= 0 ? p.window[block].mean : tree->mean;
  c.nu = sensor.Innovation(obs.z, sensor.Predict(p.pose, l, &c.H_x, &c.H_m));
  const Eigen::MatrixXd PHt = TimesHt(p.window_covariance, c);
  c.S = c.H_x * PHt.topRows<3>() + obs.R;
  if (block >= 0) c.S += c.H_m * PHt.middleRows(3 + 2 * block, 2);
  if (tree) c.S += c.H_m * tree->covariance * c.H_m.transpose();
  const Eigen::LLT<Eigen::Matrix2d> llt(c.S);
  if (llt.info() != Eigen::Success) return c;
  c.distance_chi2 = c.nu.dot(llt.solve(c.nu));
  c.log_likelihood = LogGaussianDensity(c.distance_chi2, c.S);
  return c;
}

// The EKF update of the window's state in O(n²): P Hᵀ once, then K S Kᵀ.
void UpdateWindow(FastSlamParticle& p, const WindowComparison& c) {
  Eigen::MatrixXd& P = p.window_covariance;
  const Eigen::MatrixXd PHt = TimesHt(P, c);
  const Eigen::MatrixXd K = PHt * c.S.inverse();
  const Eigen::VectorXd dx = K * c.nu;
  p.pose = Pose2(p.pose.vector() + dx.head<3>());
  for (std::size_t j = 0; j < p.window.size(); ++j) p.window[j].mean += dx.segment<2>(3 + 2 * j);
  P -= K * c.S * K.transpose();
  P = 0.5 * (P + P.transpose()).eval();
}

// SPEC S2, Eq. 8 in the window: the new landmark joins the state, correlated with the pose.
int AugmentWindow(FastSlamParticle& p, const PointObservation& obs,
                  const PointSensorModel& sensor) {
  Eigen::Matrix<double, 2, 3> G_x;
  Eigen::Matrix2d G_z;
  const Eigen::Vector2d l = sensor.Invert(p.pose, obs.z, &G_x, &G_z);
  Eigen::MatrixXd& P = p.window_covariance;
  const int n = static_cast<int>(P.rows());
  const Eigen::MatrixXd cross = G_x * P.topRows<3>();  // 2 × n
  P.conservativeResize(n + 2, n + 2);
  P.block(n, 0, 2, n) = cross;
  P.block(0, n, n, 2) = cross.transpose();
  P.block<2, 2>(n, n) =
      G_x * P.topLeftCorner<3, 3>() * G_x.transpose() + G_z * obs.R * G_z.transpose();
  p.window.push_back({-1, l});
  return static_cast<int>(p.window.size()) - 1;
}

WindowComparison BestInWindow(const FastSlamParticle& p, const std::vector<Candidate>& candidates,
                              const std::vector<bool>& window_taken, const PointObservation& obs,
                              const ScanInputs& scan, double& nearest_chi2) {
  WindowComparison best;
  auto consider = [&](const WindowComparison& c) {
    nearest_chi2 = std::min(nearest_chi2, c.distance_chi2);
    const bool gated = scan.params.new_landmark_test != NewLandmarkTest::kMahalanobis ||
                       c.distance_chi2 <= scan.params.gate_chi2;
    if (gated && c.log_likelihood > best.log_likelihood) best = c;
  };
  for (std::size_t j = 0; j < p.window.size(); ++j) {
    if (p.window[j].slot >= 0 && !window_taken[j]) {
      consider(CompareWindow(p, static_cast<int>(j), -1, nullptr, obs, scan.sensor));
    }
  }
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (!candidates[i].taken) {
      const int k = static_cast<int>(i);
      consider(CompareWindow(p, -1, k, &candidates[k].landmark, obs, scan.sensor));
    }
  }
  return best;
}

// Draws the pose from the window's Gaussian and conditions each window landmark on it; they go
// to the tree (or, made in this scan, to `out.created`), and the window empties.
void DrawWindow(FastSlamParticle& p, const std::vector<int>& window_observation, Rng& rng,
                ParticleUpdate& out) {
  Eigen::MatrixXd& P = p.window_covariance;
  const Eigen::Matrix3d P_xx = P.topLeftCorner<3, 3>();
  const Eigen::Vector3d d = P_xx.isZero(0.0) ? Eigen::Vector3d::Zero()
                                             : Eigen::Vector3d(rng.MultivariateNormal(P_xx));
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(P_xx);
  for (std::size_t j = 0; j < p.window.size(); ++j) {
    const int at = 3 + 2 * static_cast<int>(j);
    FastSlamLandmark l;
    l.mean = p.window[j].mean;
    l.covariance = P.block<2, 2>(at, at);
    if (!P_xx.isZero(0.0)) {
      const Eigen::Matrix<double, 2, 3> gain = ldlt.solve(P.block<3, 2>(0, at)).transpose();
      l.mean += gain * d;
      l.covariance -= gain * P.block<3, 2>(0, at);
      l.covariance = 0.5 * (l.covariance + l.covariance.transpose()).eval();
    }
    if (p.window[j].slot >= 0) {
      p.landmarks.Set(p.window[j].slot, l);
    } else {
      out.created[window_observation[j]] = l;
      out.created_in_window[window_observation[j]] = -1;
    }
  }
  p.pose = Pose2(p.pose.vector() + d);
  p.window.clear();
  P = Eigen::Matrix3d::Zero();
}

// What one scan has decided so far: the particle's landmarks near its pose, which window
// landmarks are taken, which sighting made each landmark that joined the window in this scan,
// and the landmarks of the tree matched (candidate, sighting).
struct ScanState {
  std::vector<Candidate> candidates;
  std::vector<bool> window_taken;
  std::vector<int> window_observation;
  std::vector<std::pair<int, int>> tree_matches;
};

// One sighting: matched (an EKF update of the window's state), new (it joins the window) or
// dropped, by the particle's test, and its weight factor as FastSLAM 2.0's (Eq. 21 or p0).
AssociationDecision DecideInWindow(FastSlamParticle& p, ScanState& state, int i,
                                   const ScanInputs& scan, ParticleUpdate& out) {
  const PointObservation& obs = scan.observations[i];
  const double log_p0 = LogNewLandmarkLikelihood(obs.R, scan.params.new_landmark_chi2);
  const bool mahalanobis = scan.params.new_landmark_test == NewLandmarkTest::kMahalanobis;
  double nearest = kInfinity;
  const WindowComparison best =
      BestInWindow(p, state.candidates, state.window_taken, obs, scan, nearest);
  AssociationDecision d;
  d.distance_chi2 = nearest;
  const bool matched = best.block >= 0 || best.candidate >= 0;
  if (!matched || !(mahalanobis || best.log_likelihood > log_p0)) {
    out.log_weight += log_p0;
    if (mahalanobis && nearest <= scan.params.new_landmark_chi2) return d;  // dropped
    d.kind = AssociationDecision::Kind::kNew;
    out.created_in_window[i] = AugmentWindow(p, obs, scan.sensor);
    out.created[i].mean = p.window.back().mean;  // where the filter files the new slot
    state.window_taken.push_back(true);
    state.window_observation.push_back(i);
    return d;
  }
  out.log_weight += best.log_likelihood;
  UpdateWindow(p, best);
  d.kind = AssociationDecision::Kind::kMatched;
  d.distance_chi2 = best.distance_chi2;
  if (best.block >= 0) {
    state.window_taken[best.block] = true;
    d.landmark = p.window[best.block].slot;
  } else {
    state.candidates[best.candidate].taken = true;
    state.tree_matches.push_back({best.candidate, i});
    d.landmark = state.candidates[best.candidate].slot;
  }
  return d;
}

}  // namespace

// One scan with delayed sampling: every sighting is an EKF update of the window's state (a
// window landmark, a landmark of the tree, or a new one joining the window); the pose is drawn
// only if a landmark of the tree was matched or the window grew past its limit.
void UpdateWithWindow(FastSlamParticle& p, const ScanInputs& scan, Rng& rng,
                      ParticleUpdate& out) {
  ScanState state{GatherCandidates(p, scan), std::vector<bool>(p.window.size(), false),
                  std::vector<int>(p.window.size(), -1), {}};
  out.decisions.clear();
  out.log_weight = 0.0;
  out.created.assign(scan.observations.size(), FastSlamLandmark{});
  for (std::size_t i = 0; i < scan.observations.size(); ++i) {
    out.decisions.push_back(DecideInWindow(p, state, static_cast<int>(i), scan, out));
  }
  if (!state.tree_matches.empty() ||
      static_cast<int>(p.window.size()) > scan.params.window_max_landmarks) {
    DrawWindow(p, state.window_observation, rng, out);
    for (const auto& [c, i] : state.tree_matches) {
      UpdateLandmark(state.candidates[c], p.pose, scan.observations[i], scan.sensor);
    }
    WriteBack(p, state.candidates);
  }
  p.pose_covariance = p.window_covariance.topLeftCorner<3, 3>();
}

}  // namespace slamkit::fastslam_detail
