#include "slamkit/filters/localization/monte_carlo_localization.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Eigenvalues>

#include "slamkit/core/angle.hpp"
#include "slamkit/filters/particles/resampling.hpp"

namespace slamkit {

namespace {

void Require(bool ok, const char* name, const char* what) {
  if (!ok) throw std::invalid_argument(std::string("MclParams: ") + name + " must be " + what);
}

// A histogram bin of KLD-sampling, packed into one key.
std::uint64_t BinKey(const Pose2& p, const MclParams& params) {
  const auto cell = [](double v, double size) {
    return std::uint64_t(std::int64_t(std::floor(v / size)) & 0x1fffff);
  };
  return cell(p.x(), params.bin_xy_m) << 42 | cell(p.y(), params.bin_xy_m) << 21 |
         cell(WrapAngle(p.theta()) + M_PI, params.bin_theta_rad);
}

}  // namespace

int KldParticleCount(int bins, double error, double quantile) {
  if (bins <= 1) return 1;
  const double k = bins - 1;
  const double a = 2.0 / (9.0 * k);
  return int(std::ceil(k / (2.0 * error) * std::pow(1.0 - a + std::sqrt(a) * quantile, 3)));
}

MonteCarloLocalization::MonteCarloLocalization(std::shared_ptr<const LikelihoodField> field,
                                               const MclParams& params)
    : field_(std::move(field)), params_(params), rng_(params.seed) {
  if (!field_) throw std::invalid_argument("MonteCarloLocalization: no map");
  Require(params.min_particles >= 1, "min_particles", ">= 1");
  Require(params.max_particles >= params.min_particles, "max_particles", ">= min_particles");
  Require(params.kld_error > 0.0 && params.kld_quantile > 0.0, "kld_error and kld_quantile",
          "> 0");
  Require(params.bin_xy_m > 0.0 && params.bin_theta_rad > 0.0, "the bin sizes", "> 0");
  Require(params.max_beams >= 1, "max_beams", ">= 1");
  Require(params.sigma_hit_m > 0.0 && params.usable_range_m > 0.0,
          "sigma_hit_m and usable_range_m", "> 0");
  Require(params.z_hit >= 0.0 && params.z_rand > 0.0, "z_hit and z_rand", ">= 0 and > 0");
  Require(params.alpha_slow >= 0.0 && params.alpha_fast >= params.alpha_slow, "alpha_fast",
          ">= alpha_slow >= 0");
}

void MonteCarloLocalization::InitialiseAt(const Pose2& pose) {
  poses_.resize(params_.max_particles);
  for (Pose2& p : poses_) {
    p = Pose2(pose.x() + rng_.Normal(0.0, params_.initial_sigma_xy_m),
              pose.y() + rng_.Normal(0.0, params_.initial_sigma_xy_m),
              WrapAngle(pose.theta() + rng_.Normal(0.0, params_.initial_sigma_theta_rad)));
  }
  Summarise(std::vector<double>(poses_.size(), 1.0 / double(poses_.size())));
}

void MonteCarloLocalization::InitialiseGlobally() {
  if (field_->FreeCells().empty()) {
    throw std::invalid_argument("MonteCarloLocalization: the map has no free cell");
  }
  poses_.resize(params_.max_particles);
  for (Pose2& p : poses_) p = RandomPose();
  Summarise(std::vector<double>(poses_.size(), 1.0 / double(poses_.size())));
}

// A pose uniform over the free cells (anywhere inside one) and the headings.
Pose2 MonteCarloLocalization::RandomPose() {
  const std::vector<Eigen::Vector2d>& cells = field_->FreeCells();
  const std::size_t i =
      std::min(cells.size() - 1, std::size_t(rng_.Uniform() * double(cells.size())));
  const double half = 0.5 * field_->resolution();
  return Pose2(cells[i].x() + rng_.Uniform(-half, half), cells[i].y() + rng_.Uniform(-half, half),
               rng_.Uniform(-M_PI, M_PI));
}

bool MonteCarloLocalization::ProcessScan(const LaserScan& scan) {
  if (poses_.empty()) throw std::logic_error("MonteCarloLocalization: not initialised");
  last_odometry_ = scan.odometry;
  if (!last_update_odometry_) {
    last_update_odometry_ = scan.odometry;
    return false;
  }
  const Pose2 delta = last_update_odometry_->Between(scan.odometry);
  if (delta.translation().norm() < params_.update_min_d_m &&
      std::abs(delta.theta()) < params_.update_min_a_rad) {
    return false;
  }
  Predict(delta);
  ResampleKld(Weigh(scan));
  last_update_odometry_ = scan.odometry;
  ++updates_;
  return true;
}

Pose2 MonteCarloLocalization::CurrentPose() const {
  if (!last_update_odometry_) return status_.estimate;
  return status_.estimate.Compose(last_update_odometry_->Between(last_odometry_));
}

// Probabilistic Robotics Table 5.6 (sample_motion_model_odometry) for every particle.
void MonteCarloLocalization::Predict(const Pose2& delta) {
  for (Pose2& p : poses_) p = SampleOdometryMotion(p, delta, params_.motion, rng_);
}

// Probabilistic Robotics Table 6.3 (likelihood_field_range_finder_model), in logs, over at most
// max_beams beams spread evenly over the scan (AMCL's choice of beams).
std::vector<double> MonteCarloLocalization::Weigh(const LaserScan& scan) const {
  const int n = static_cast<int>(scan.ranges_m.size());
  const int step = std::max(1, n / params_.max_beams);
  std::vector<Eigen::Vector2d> ends;  // in the robot frame
  for (int i = 0; i < n; i += step) {
    if (!scan.IsReturn(i) || scan.ranges_m[i] > params_.usable_range_m) continue;
    const double a = scan.BeamAngle(i), r = scan.ranges_m[i];
    ends.push_back(scan.laser_offset.TransformFrom(Eigen::Vector2d(r * std::cos(a),
                                                                   r * std::sin(a))));
  }
  const double inv_two_var = 0.5 / (params_.sigma_hit_m * params_.sigma_hit_m);
  const double random = params_.z_rand / params_.usable_range_m;
  std::vector<double> log_weights(poses_.size(), 0.0);
  for (std::size_t k = 0; k < poses_.size(); ++k) {
    const Eigen::Matrix2d R = poses_[k].rotation();
    const Eigen::Vector2d t = poses_[k].translation();
    double sum = 0.0;
    for (const Eigen::Vector2d& e : ends) {
      const double d = field_->DistanceM(R * e + t);
      sum += std::log(params_.z_hit * std::exp(-d * d * inv_two_var) + random);
    }
    // Per beam, so that augmented MCL's averages do not depend on how many beams returned.
    log_weights[k] = ends.empty() ? 0.0 : sum / double(ends.size());
  }
  return log_weights;
}

// KLD-sampling (Fox 2003, Table 1) from the weighted particles, with augmented MCL's random
// particles (Probabilistic Robotics Table 8.3): draws until the occupied bins' bound is met.
void MonteCarloLocalization::ResampleKld(const std::vector<double>& per_beam_log_weights) {
  // A particle's weight is its mean per-beam likelihood to the power max_beams: a scan with
  // fewer returns weighs the particles no less sharply. The per-beam likelihood, averaged over
  // the particles, drives the recovery.
  const double beams = params_.independent_beams;
  std::vector<double> log_weights(per_beam_log_weights.size());
  double w_avg = 0.0;
  for (std::size_t k = 0; k < log_weights.size(); ++k) {
    log_weights[k] = per_beam_log_weights[k] * beams;
    w_avg += std::exp(per_beam_log_weights[k]);
  }
  w_avg /= double(log_weights.size());
  const std::vector<double> weights = NormaliseLogWeights(log_weights);
  Summarise(weights);
  double p_random = 0.0;
  if (params_.alpha_slow > 0.0) {
    w_slow_ = w_slow_ == 0.0 ? w_avg : w_slow_ + params_.alpha_slow * (w_avg - w_slow_);
    w_fast_ = w_fast_ == 0.0 ? w_avg : w_fast_ + params_.alpha_fast * (w_avg - w_fast_);
    if (recovery_allowed_) p_random = std::max(0.0, 1.0 - w_fast_ / w_slow_);
  }
  std::vector<double> cumulative(weights.size());
  double total = 0.0;
  for (std::size_t k = 0; k < weights.size(); ++k) cumulative[k] = total += weights[k];
  std::vector<Pose2> next;
  std::unordered_set<std::uint64_t> bins;
  int randoms = 0;
  while (int(next.size()) < params_.max_particles) {
    if (p_random > 0.0 && rng_.Uniform() < p_random) {
      next.push_back(RandomPose());
      ++randoms;
    } else {
      const auto it = std::upper_bound(cumulative.begin(), cumulative.end(),
                                       rng_.Uniform() * total);
      next.push_back(poses_[std::min<std::size_t>(it - cumulative.begin(), poses_.size() - 1)]);
    }
    bins.insert(BinKey(next.back(), params_));
    const int wanted = std::max(params_.min_particles,
                                KldParticleCount(int(bins.size()), params_.kld_error,
                                                 params_.kld_quantile));
    if (int(next.size()) >= wanted) break;
  }
  // Not AMCL's reset of both averages after an injection: that restarts the long-term average at
  // the lost robot's likelihood, and no further particles come while it stays lost.
  status_.random_fraction = double(randoms) / double(next.size());
  poses_ = std::move(next);
}

namespace {

// The weighted mean of the particles in the heaviest position bin (`keys`: each particle's).
Eigen::Vector2d HeaviestBinMean(const std::vector<Pose2>& poses,
                                const std::vector<double>& weights,
                                const std::vector<std::uint64_t>& keys) {
  std::unordered_map<std::uint64_t, double> bin_weight;
  std::uint64_t best_bin = 0;
  double best_weight = -1.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const double w = bin_weight[keys[k]] += weights[k];
    if (w > best_weight) {
      best_weight = w;
      best_bin = keys[k];
    }
  }
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double in_bin = 0.0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    if (keys[k] != best_bin) continue;
    centre += weights[k] * poses[k].translation();
    in_bin += weights[k];
  }
  return centre / std::max(in_bin, 1e-300);
}

}  // namespace

// The estimate: the weighted mean of the particles within cluster_radius_m of the heaviest
// position bin's mean (AMCL reports its heaviest cluster's mean); the spread is all particles'.
void MonteCarloLocalization::Summarise(const std::vector<double>& weights) {
  MclParams xy_only = params_;
  xy_only.bin_theta_rad = 4.0 * M_PI;  // one heading bin
  std::vector<std::uint64_t> keys(poses_.size());
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < poses_.size(); ++k) {
    keys[k] = BinKey(poses_[k], xy_only);
    mean += weights[k] * poses_[k].translation();
  }
  const Eigen::Vector2d centre = HeaviestBinMean(poses_, weights, keys);
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  double c = 0.0, s = 0.0, in_cluster = 0.0;
  for (std::size_t k = 0; k < poses_.size(); ++k) {
    const Eigen::Vector2d d = poses_[k].translation() - mean;
    cov += weights[k] * d * d.transpose();
    if ((poses_[k].translation() - centre).norm() > params_.cluster_radius_m) continue;
    xy += weights[k] * poses_[k].translation();
    c += weights[k] * std::cos(poses_[k].theta());
    s += weights[k] * std::sin(poses_[k].theta());
    in_cluster += weights[k];
  }
  if (in_cluster > 0.0) xy /= in_cluster;
  status_.estimate = Pose2(xy.x(), xy.y(), std::atan2(s, c));
  const Eigen::Vector2d eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov, Eigen::EigenvaluesOnly).eigenvalues();
  status_.spread_m = std::sqrt(std::max(0.0, eigenvalues.maxCoeff()));
  status_.particles = int(poses_.size());
}

}  // namespace slamkit
