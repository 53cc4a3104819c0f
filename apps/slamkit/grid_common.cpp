#include "grid_common.hpp"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <cerrno>
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <system_error>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"

#include "slamkit/io/grid_writers.hpp"
#include "slamkit/io/writers.hpp"
#include "slamkit/report/figures.hpp"

namespace slamkit::app {

namespace {

CLI::Validator NumberCheck(const std::string& description, bool (*ok)(double)) {
  return CLI::Validator(
      [description, ok](std::string& text) -> std::string {
        double value = 0.0;
        if (!CLI::detail::lexical_cast(text, value)) {
          return fmt::format("must be a number {}, got '{}'", description, text);
        }
        if (!std::isfinite(value) || !ok(value)) {
          return fmt::format("must be {}, got {}", description, text);
        }
        return {};
      },
      "NUMBER " + description);
}

}  // namespace

// "1-5", "1,3,7" or "2" as the list of seeds.
std::vector<std::uint64_t> ParseSeeds(const std::string& text) {
  std::vector<std::uint64_t> seeds;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string part = text.substr(start, comma - start);
    const std::size_t dash = part.find('-');
    try {
      std::size_t used = 0;
      const std::uint64_t lo = std::stoull(part.substr(0, dash), &used);
      if (used != part.substr(0, dash).size() || part[0] == '-') throw std::invalid_argument("");
      std::uint64_t hi = lo;
      if (dash != std::string::npos) {
        const std::string rest = part.substr(dash + 1);
        hi = std::stoull(rest, &used);
        if (used != rest.size() || rest.empty() || rest[0] == '-') throw std::invalid_argument("");
      }
      if (hi < lo || hi - lo >= 1000) throw std::invalid_argument("");
      for (std::uint64_t s = lo; s <= hi; ++s) seeds.push_back(s);
    } catch (const std::exception&) {
      throw InputError(fmt::format("--seeds '{}': expected seeds such as 1-5 or 1,3,7 (a range "
                                   "of at most 1000)",
                                   text));
    }
    start = comma + 1;
  }
  return seeds;
}

const char* AssociationName(AssociationMethod m) {
  switch (m) {
    case AssociationMethod::kKnown: return "known";
    case AssociationMethod::kJointCompatibility: return "joint-compatibility";
    case AssociationMethod::kMaximumLikelihood: return "maximum-likelihood";
    case AssociationMethod::kGlobalNearestNeighbour: return "global-nearest-neighbour";
    case AssociationMethod::kNearestNeighbour: break;
  }
  return "nearest-neighbour";
}

CLI::Validator PositiveNumber() {
  return NumberCheck("> 0", [](double v) { return v > 0.0; });
}

CLI::Validator NonNegativeNumber() {
  return NumberCheck(">= 0", [](double v) { return v >= 0.0; });
}

CLI::Validator SeedNumber() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const bool digits =
            !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        if (!digits || !CLI::detail::lexical_cast(text, value)) {
          return fmt::format("must be a whole number from 0 to 18446744073709551615, got '{}'",
                             text);
        }
        return {};
      },
      "SEED");
}

OutputDir::OutputDir(const std::string& out) {
  namespace fs = std::filesystem;
  if (out.empty()) throw InputError("--out: the output directory is empty");
  std::error_code ec;
  fs::path target = fs::absolute(fs::path(out), ec).lexically_normal();
  if (ec) throw InputError(fmt::format("--out {}: {}", out, ec.message()));
  if (!target.has_filename()) target = target.parent_path();  // "out/" and "."
  if (target == target.root_path()) {
    throw InputError(fmt::format("--out {}: cannot replace the root directory", out));
  }
  const fs::file_status status = fs::status(target, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) {
      throw InputError(fmt::format("--out {}: exists and is not a directory", out));
    }
    // The run replaces the whole directory: only an empty one or an earlier output.
    const bool empty = fs::is_empty(target, ec);
    if (!ec && !empty && !fs::exists(target / "metrics.json")) {
      throw InputError(fmt::format(
          "--out {}: exists and holds other files than an earlier slamkit output (no "
          "metrics.json); the run would replace it: give a new directory",
          out));
    }
  }
  target_ = target;
  fs::create_directories(target.parent_path(), ec);
  if (ec) throw InputError(fmt::format("--out {}: cannot create it: {}", out, ec.message()));
  // The run writes beside the target, then renames: either the old output or the whole new one.
  std::string staging =
      (target.parent_path() / ("." + target.filename().string() + ".partial-XXXXXX")).string();
  if (mkdtemp(staging.data()) == nullptr) {
    throw InputError(fmt::format("--out {}: cannot create it: {}", out, std::strerror(errno)));
  }
  const mode_t mask = umask(0);  // mkdtemp makes 0700: give it the mode mkdir would
  umask(mask);
  chmod(staging.c_str(), 0777 & ~mask);
  staging_ = staging;
}

OutputDir::~OutputDir() {
  if (committed_) return;
  std::error_code ec;
  std::filesystem::remove_all(staging_, ec);
}

void OutputDir::Commit() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(target_, ec)) {
    fs::rename(staging_, target_);  // throws (exit 1) with both names
  } else {
    // Swap the two in one step, then remove the old output (now at the staging name).
    if (renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0) {
      throw std::system_error(errno, std::generic_category(),
                              fmt::format("cannot move {} to {}", staging_.string(),
                                          target_.string()));
    }
  }
  committed_ = true;
  fs::remove_all(staging_, ec);
}

std::vector<CLI::Option*> AddGridFilterOptions(CLI::App* cmd, RbpfGridSlamParams& p) {
  const std::size_t before = cmd->get_options().size();
  cmd->add_option("--particles", p.particles, "particles")->capture_default_str()
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--seed", p.seed, "random seed of the filter")
      ->check(SeedNumber())
      ->capture_default_str();
  cmd->add_option("--linear-update", p.linear_update_m, "update after driving this far [m]")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--angular-update", p.angular_update_rad, "update after turning this far [rad]")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--usable-range", p.usable_range_m,
                  "laser range used [m]: in the maps, the matching and the tracking")
      ->capture_default_str()->check(PositiveNumber());
  cmd->add_option("--resolution", p.grid.resolution_m, "map cell size [m]")
      ->capture_default_str()->check(PositiveNumber());
  cmd->add_option("--srr", p.motion.srr, "odometry noise: m per m driven")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--srt", p.motion.srt, "odometry noise: m per rad turned")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--str", p.motion.str, "odometry noise: rad per m driven")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--stt", p.motion.stt, "odometry noise: rad per rad turned")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_flag_callback(
      "--match-proposal", [&p] { p.proposal = ProposalScheme::kScanMatch; },
      "take each particle's scan match as its pose (ROS GMapping) instead of drawing from the "
      "Gaussian fitted around it (Grisetti et al. 2007)");
  // Either order of the two flags gives the same mode: --no-tracking wins.
  cmd->add_flag_callback(
      "--odometry-motion",
      [&p] {
        if (p.tracking_mode == TrackingMode::kTrackedMotion) {
          p.tracking_mode = TrackingMode::kTrackOnly;
        }
      },
      "move the particles by raw odometry between updates, not by the tracked motion");
  cmd->add_flag_callback(
      "--no-tracking", [&p] { p.tracking_mode = TrackingMode::kOff; },
      "poses of scans between updates by odometry alone (as GMapping), not tracked against the "
      "best map; the particles then move by odometry too");
  cmd->add_option("--resampling", p.resampling.scheme, "resampling scheme")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, ResamplingScheme>{{"systematic", ResamplingScheme::kSystematic},
                                                  {"stratified", ResamplingScheme::kStratified},
                                                  {"multinomial", ResamplingScheme::kMultinomial}},
          CLI::ignore_case))
      ->default_str("systematic");
  cmd->add_option("--tracking-prior-xy", p.tracking.prior_sigma_xy_m,
                  "tracking: sigma of the translation prior around the odometry guess [m] "
                  "(0: none)")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--tracking-max-correction", p.tracking_max_correction_m,
                  "tracking: largest translation correction accepted [m]")
      ->capture_default_str()->check(NonNegativeNumber());
  cmd->add_option("--tracking-max-correction-angle", p.tracking_max_correction_rad,
                  "tracking: largest heading correction accepted [rad]")
      ->capture_default_str()->check(NonNegativeNumber());
  std::vector<CLI::Option*> all = cmd->get_options([](CLI::Option*) { return true; });
  return {all.begin() + static_cast<std::ptrdiff_t>(before), all.end()};
}

int WriteGridOutputs(const std::filesystem::path& dir, const GridRunResult& result,
                     const Trajectory& odometry, const std::string& title) {
  std::filesystem::create_directories(dir);
  WritePoseText(dir / "trajectory.txt", result.trajectory);
  int moved = 0;
  WriteTumTrajectory(dir / "trajectory.tum", WithIncreasingTimes(result.trajectory, 1e-6, &moved));
  if (!odometry.empty()) WriteTumTrajectory(dir / "odometry.tum", WithIncreasingTimes(odometry));
  WriteOccupancyGridPgm(dir / "map.pgm", result.map);
  // map.png is the figure (cropped, the paths over it, a scale bar); map.pgm holds every cell.
#ifdef __GLIBC__
  // The filter's particles and maps are gone by now, but glibc keeps their freed pages; handing
  // them back first keeps the figure's canvas from adding to the peak (Intel: 145 -> 116 MiB).
  malloc_trim(0);
#endif
  MapSheetData figure;
  figure.columns = 1;
  figure.panel_px = 1200;
  figure.panels.push_back({title, RenderOccupancyImage(result.map), result.trajectory, odometry});
  WriteMapContactSheet(dir / "map.png", figure);
  return moved;
}

void PrintGridRun(const std::string& source, const GridRunResult& result, int particles) {
  fmt::print("{}: {} scans, {} updates, {} resamples, {} particles\n", source, result.scans,
             result.updates, result.resamples, particles);
  fmt::print("  {:<28}{:>12.2f}\n", "wall time [s]", result.wall_time_s);
  fmt::print("  {:<28}{:>12.1f}\n", "scans per second", result.scans / result.wall_time_s);
  fmt::print("  {:<28}{:>12.1f}\n", "peak memory [MiB]", PeakRssMib());
  PrintHeadingDrift(result.odometry_heading_drift);
  if (result.heading_drift_in_use_rad_per_m != 0.0) {
    fmt::print("  {:<28}{:>12.5f}\n", "drift applied at the end",
               result.heading_drift_in_use_rad_per_m);
  }
}

void PrintHeadingDrift(const std::optional<HeadingDriftFit>& fit) {
  if (!fit) return;
  fmt::print("  {:<28}{:>12.5f}  (rms turn error per window {:.3f} -> {:.3f} rad)\n",
             "odometry drift [rad/m]", fit->drift_rad_per_m, fit->rms_before_rad,
             fit->rms_after_rad);
}

void PrintComparison(const std::string& against, const ReferenceComparison& c) {
  fmt::print("  {:<28}{:>12}\n", fmt::format("ATE vs {} [m]", against),
             fmt::format("{:.4f} rms, {:.4f} max", c.ate.rmse_m, c.ate.max_m));
  fmt::print("  {:<28}{:>12}\n", "RPE translation [m]",
             fmt::format("{:.4f} ± {:.4f}", c.rpe.trans_mean_m, c.rpe.trans_std_m));
  fmt::print("  {:<28}{:>12}\n", "RPE rotation [deg]",
             fmt::format("{:.3f} ± {:.3f}", c.rpe.rot_mean_deg, c.rpe.rot_std_deg));
}

}  // namespace slamkit::app
