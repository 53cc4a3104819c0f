#include "grid_options.hpp"

namespace slamkit::app {

void AddGridFilterOptions(CLI::App* cmd, RbpfGridSlamParams& p) {
  cmd->add_option("--particles", p.particles, "particles")->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--seed", p.seed, "random seed of the filter")->capture_default_str();
  cmd->add_option("--linear-update", p.linear_update_m, "update after driving this far [m]")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--angular-update", p.angular_update_rad, "update after turning this far [rad]")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--usable-range", p.insertion.usable_range_m, "laser range used [m]")
      ->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--resolution", p.grid.resolution_m, "map cell size [m]")
      ->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--srr", p.motion.srr, "odometry noise: m per m driven")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--srt", p.motion.srt, "odometry noise: m per rad turned")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--str", p.motion.str, "odometry noise: rad per m driven")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_option("--stt", p.motion.stt, "odometry noise: rad per rad turned")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  cmd->add_flag("!--match-proposal", p.gaussian_proposal,
                "take each particle's scan match as its pose (ROS GMapping) instead of drawing "
                "from the Gaussian fitted around it (Grisetti et al. 2007)");
  cmd->add_flag("!--odometry-motion", p.motion_from_tracking,
                "move the particles by raw odometry between updates, not by the tracked motion");
  cmd->add_flag("!--no-tracking", p.track_between_updates,
                "poses of scans between updates by odometry alone (as GMapping), not tracked "
                "against the best map; the particles then move by odometry too");
}

void FinishGridFilterOptions(RbpfGridSlamParams& p) {
  p.matcher.usable_range_m = p.insertion.usable_range_m;
  p.tracking.usable_range_m = p.insertion.usable_range_m;
}

}  // namespace slamkit::app
