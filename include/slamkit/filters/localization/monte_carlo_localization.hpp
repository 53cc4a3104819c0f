#pragma once

// Monte Carlo localisation on a saved map (Dellaert, Fox, Burgard and Thrun 1999) with
// KLD-sampling (Fox, IJRR 2003), the likelihood-field beam model and augmented MCL's random
// particles for recovery (Thrun, Burgard and Fox, Probabilistic Robotics, Tables 8.2-8.4): what
// ROS AMCL runs, with AMCL's defaults unless said otherwise.

#include <memory>
#include <optional>
#include <vector>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/maps/likelihood_field.hpp"
#include "slamkit/models/odometry_sampling.hpp"

namespace slamkit {

struct MclParams {
  int min_particles = 500;          // AMCL min_particles is 100; 500 holds Intel's corridors
  // Only global localisation (and recovery) fills the set: KLD-sampling keeps a tracked robot
  // near min_particles. AMCL's 5000 settled in the wrong room of Intel from a global start;
  // 20000 found the right one within 160 scans.
  int max_particles = 20000;
  double kld_error = 0.01;          // ε of KLD-sampling (AMCL kld_err)
  double kld_quantile = 2.326;      // z_{1-δ} of KLD-sampling, δ = 0.01 (AMCL kld_z 0.99)
  double bin_xy_m = 0.5;            // KLD-sampling's histogram bins (AMCL's)
  double bin_theta_rad = 0.174533;  // 10°
  // Odometry noise: AMCL's odom_alpha1-4 (0.2 each). The grid filter's tighter noise (which its
  // scan matching makes up for) lost Intel's corridors here.
  OdometryNoiseParams motion{0.2, 0.2, 0.2, 0.2};
  double update_min_d_m = 0.2;      // filter update after driving this far (AMCL update_min_d)
  double update_min_a_rad = 0.5236; // or turning this far (AMCL update_min_a, π/6)
  int max_beams = 60;               // beams used per update, evenly spread (AMCL laser_max_beams)
  // A particle's weight: its mean per-beam likelihood to this power, as if the scan gave this
  // many independent beams (fewer than used: neighbouring beams' errors are correlated, and the
  // full product over the beams collapses the particles onto a few).
  double independent_beams = 60.0;
  double sigma_hit_m = 0.2;         // the likelihood field's Gaussian (AMCL laser_sigma_hit)
  double z_hit = 0.95;              // mixture weights (AMCL laser_z_hit, laser_z_rand)
  double z_rand = 0.05;
  double usable_range_m = 50.0;     // longer readings (and no returns) are not used
  // Augmented MCL: random particles while the short-term average likelihood falls below the
  // long-term one (Probabilistic Robotics Table 8.3; AMCL's recovery_alpha_slow/fast). Off (0) by
  // default, as in AMCL: on Intel, where the map does not explain every scan (people, doors),
  // the random particles drew the estimate away; 0.001 and 0.1 recover a kidnapped robot.
  double alpha_slow = 0.0;
  double alpha_fast = 0.0;
  double initial_sigma_xy_m = 0.5;  // spread around --initial-pose (AMCL initial_cov 0.25 m²)
  double initial_sigma_theta_rad = 0.2618;  // π/12 (AMCL initial_cov_aa (π/12)²)
  double cluster_radius_m = 1.0;   // the estimate: mean of the particles this near the best bin
  double converged_spread_m = 0.5; // converged: the particles' position spread below this
  std::uint64_t seed = 1;
};

// The filter's summary after an update.
struct MclStatus {
  Pose2 estimate;
  double spread_m = 0.0;        // sqrt of the largest eigenvalue of the particles' xy covariance
  int particles = 0;
  double random_fraction = 0.0; // particles drawn at random in the last resampling
};

class MonteCarloLocalization {
 public:
  // Throws std::invalid_argument for parameters out of range (named).
  MonteCarloLocalization(std::shared_ptr<const LikelihoodField> field, const MclParams& params);

  // Particles drawn around `pose` (initial_sigma_*), or uniformly over the free cells and headings.
  void InitialiseAt(const Pose2& pose);
  void InitialiseGlobally();

  // Moves the particles by the odometry since the last update and, once it exceeds
  // update_min_d_m or update_min_a_rad, weighs them on `scan` and resamples. Returns whether it
  // updated. The first scan only records the odometry.
  bool ProcessScan(const LaserScan& scan);

  // The estimate at the last scan: the last update's composed with the odometry since.
  Pose2 CurrentPose() const;
  const MclStatus& status() const { return status_; }
  bool Converged() const { return status_.spread_m < params_.converged_spread_m; }
  const std::vector<Pose2>& particles() const { return poses_; }
  int updates() const { return updates_; }
  // Whether augmented MCL may draw random particles at the next updates (when it is on): a
  // caller with other evidence that the robot is where the filter thinks (its scans match the
  // map there) holds them back. The likelihood averages are kept up to date either way.
  void AllowRecovery(bool allowed) { recovery_allowed_ = allowed; }

 private:
  void Predict(const Pose2& delta);
  std::vector<double> Weigh(const LaserScan& scan) const;
  double BeamLogLikelihood(const LaserScan& scan, const Pose2& laser, int beam) const;
  void ResampleKld(const std::vector<double>& log_weights);
  Pose2 RandomPose();
  void Summarise(const std::vector<double>& weights);

  std::shared_ptr<const LikelihoodField> field_;
  MclParams params_;
  Rng rng_;
  std::vector<Pose2> poses_;
  std::optional<Pose2> last_update_odometry_;
  Pose2 last_odometry_;
  MclStatus status_;
  double w_slow_ = 0.0;
  double w_fast_ = 0.0;
  int updates_ = 0;
  bool recovery_allowed_ = true;
};

// The number of particles KLD-sampling asks for when `bins` histogram bins are occupied (Fox
// 2003, Eq. 11): (k - 1) / (2ε) · (1 - 2/(9(k-1)) + sqrt(2/(9(k-1))) z)³.
int KldParticleCount(int bins, double error, double quantile);

}  // namespace slamkit
