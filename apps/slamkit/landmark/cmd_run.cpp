// `slamkit run`: EKF-SLAM over a real data set.
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/commands.hpp"
#include "grid/grid_outputs.hpp"
#include "common/options.hpp"
#include "common/output_dir.hpp"
#include "slamkit/core/angle.hpp"
#include "slamkit/core/cpu.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/io/isam_reader.hpp"
#include "slamkit/report/figures.hpp"
#include "slamkit/runners/landmark/filter_choice.hpp"
#include "slamkit/runners/landmark/isam_config.hpp"
#include "slamkit/runners/landmark/outputs.hpp"

namespace slamkit::app {
namespace {

struct RunOptions {
  std::string isam;
  std::string out;
  AssociationMethod association = AssociationMethod::kNearestNeighbour;
  bool known_association = false;  // the older spelling of --association known
  long jcbb_max_joint_tests = JcbbParams{}.max_joint_tests;
  double odometry_covariance_scale = 1.0;
  double sighting_covariance_scale = 1.0;
  double gate_chi2 = AssociationParams{}.gate_chi2;
  double new_landmark_chi2 = AssociationParams{}.new_landmark_chi2;
  std::vector<double> odometry_noise;  // srr, srt, str, stt
  std::vector<double> sighting_noise;  // range [m], bearing [deg]
  std::string config;
  std::string filter = "ekf";  // ekf | fastslam1 | fastslam2
  int particles = FastSlamParams{}.particles;
  std::uint64_t seed = FastSlamParams{}.seed;
  int threads = 0;
  bool association_given = false;  // --association overrides --config
  bool no_figures = false;
};

// The runner's parameters: --config, or the options (--association over either).
IsamRunParams ParamsOf(const RunOptions& o) {
  IsamRunParams params;
  if (!o.config.empty()) {
    params = LoadIsamConfig(o.config);
  } else {
    params.ekf.jcbb.max_joint_tests = o.jcbb_max_joint_tests;
    params.ekf.association.gate_chi2 = o.gate_chi2;
    params.ekf.association.new_landmark_chi2 = o.new_landmark_chi2;
    params.odometry_covariance_scale = o.odometry_covariance_scale;
    params.sighting_covariance_scale = o.sighting_covariance_scale;
    if (!o.odometry_noise.empty()) {
      params.odometry_noise = {o.odometry_noise[0], o.odometry_noise[1], o.odometry_noise[2],
                               o.odometry_noise[3]};
    }
    if (!o.sighting_noise.empty()) {
      params.sighting_sigma_range_m = o.sighting_noise[0];
      params.sighting_sigma_bearing_rad = DegToRad(o.sighting_noise[1]);
    }
  }
  if (o.known_association) {
    params.ekf.association_method = AssociationMethod::kKnown;
  } else if (o.association_given || o.config.empty()) {
    params.ekf.association_method = o.association;
  }
  return params;
}

// EKF-SLAM, or FastSLAM with the same odometry and sighting models and the same noise, its
// association the EKF's known or per-particle maximum likelihood and its new-landmark gate.
IsamRunResult RunIsam(const RunOptions& o, const IsamLog& log, const IsamRunParams& params) {
  const FilterKind kind = ParseFilterKind(o.filter);
  if (kind == FilterKind::kEkf) return RunEkfSlamOnIsam(log, params);
  FastSlamParams fastslam = FastSlamParamsFor(kind, o.particles, params.ekf);
  fastslam.threads = o.threads > 0 ? o.threads : UsableCpuCount();
  fastslam.seed = o.seed;
  return RunFastSlamOnIsam(log, params, fastslam);
}

// The run's summary on stdout (and the noise warning on stderr).
void PrintIsamRun(const RunOptions& o, const IsamRunResult& result, const IsamRunParams& params) {
  fmt::print("{}: {} poses, {} sightings, {} association\n", o.isam, result.estimate.size(),
             result.sightings, AssociationName(params.ekf.association_method));
  fmt::print("  {:<28}{:>12}\n", "landmarks mapped", result.map.landmarks.size());
  fmt::print("  {:<28}{:>12}\n", "sightings dropped", result.dropped);
  fmt::print("  {:<28}{:>12.4f}\n", "association agreement", result.association_agreement);
  if (params.score_against_merged_reference) {
    fmt::print("  {:<28}{:>12.4f}  ({} groups of the file's ids merged)\n", "  merged reference",
               result.association_agreement_merged, result.reference_merges.size());
  }
  PrintHeadingDrift(result.odometry_heading_drift);
  if (result.smoothed_reference) {
    const IsamReferenceErrors& e = *result.smoothed_reference;
    fmt::print("  {:<28}{:>12.3f}  (max {:.2f}; map {:.3f} m over {} landmarks)\n",
               "vs smoothed reference [m]", e.ate.rmse_m, e.ate.max_m, e.map_rmse_m,
               e.landmarks_compared);
  } else if (!result.smoothed_reference_failure.empty()) {
    fmt::print("  no smoothed reference: {}\n", result.smoothed_reference_failure);
  }
  fmt::print("  {:<28}{:>12.3f}\n", "wall time [s]", result.wall_time_s);
  if (result.innovation_check) {
    const InnovationCheck& check = *result.innovation_check;
    fmt::print("  {:<28}{:>12.4f}  (the gate allows {:.4f}: {})\n", "re-sightings off the gate",
               check.reobservations_outside_share, check.expected_share,
               VerdictName(check.verdict));
    const std::string warning = IsamNoiseWarning(check);
    if (!warning.empty()) PrintStderr("slamkit: warning: {}\n", warning);
  }
}

int RunIsamCommand(const RunOptions& o) {
  const IsamRunParams params = ParamsOf(o);
  if (o.filter != "ekf" &&
      (params.ekf.association_method == AssociationMethod::kJointCompatibility ||
       params.ekf.association_method == AssociationMethod::kGlobalNearestNeighbour)) {
    throw CLI::ValidationError("--filter", "jcbb and gnn are the EKF's associations: FastSLAM "
                               "associates each particle by maximum likelihood (--association "
                               "ml) or known");
  }
  const IsamLog log = ReadIsamLog(o.isam);
  OutputDir output(o.out);
  const IsamRunResult result = RunIsam(o, log, params);
  const std::filesystem::path& dir = output.staging();
  if (!o.no_figures) {
    PathFigureData figure;
    // The short name: the figure's title is one line at its font size.
    figure.title = fmt::format("{} ({})", std::filesystem::path(o.isam).filename().string(),
                               IsamParamsJson(params)["association"].get<std::string>());
    figure.estimate = result.estimate;
    figure.map = result.map;
    WritePathFigure(dir / "map.png", figure);
  }
  nlohmann::json metrics = IsamMetrics(result, params);
  metrics["filter"] = o.filter;
  if (o.filter != "ekf") {
    metrics["particles"] = o.particles;
    metrics["seed"] = o.seed;
  }
  WriteIsamOutputs(dir, metrics, result);  // metrics.json last
  output.Commit();
  PrintIsamRun(o, result, params);
  fmt::print("wrote {}\n", o.out);
  return 0;
}

// --association and --known-association; returns the first, whose count says if it was given.
CLI::Option* AddAssociationOptions(CLI::App* cmd, RunOptions& o) {
  CLI::Option* association = cmd->add_option("--association", o.association,
                  "nn (nearest neighbour), ml (maximum likelihood), gnn (global nearest "
                  "neighbour over the scan), jcbb (joint compatibility, Neira & Tardos 2001) or "
                  "known (the file's landmark ids); FastSLAM takes nn and ml both as each "
                  "particle's maximum likelihood")
      ->transform(CLI::CheckedTransformer(std::map<std::string, AssociationMethod>{
          {"nn", AssociationMethod::kNearestNeighbour},
          {"jcbb", AssociationMethod::kJointCompatibility},
          {"ml", AssociationMethod::kMaximumLikelihood},
          {"gnn", AssociationMethod::kGlobalNearestNeighbour},
          {"known", AssociationMethod::kKnown}}))
      ->default_str("nn");
  cmd->add_flag("--known-association", o.known_association, "the same as --association known")
      ->excludes("--association");
  return association;
}

// The noise and gate options that --config replaces (the two exclude each other).
std::vector<CLI::Option*> AddIsamTuningOptions(CLI::App* cmd, RunOptions& o) {
  std::vector<CLI::Option*> tuning;
  tuning.push_back(
      cmd->add_option("--jcbb-max-tests", o.jcbb_max_joint_tests,
                      "jcbb: most joint-compatibility tests per scan before taking the best found")
          ->capture_default_str()
          ->check(NonNegativeNumber()));
  tuning.push_back(cmd->add_option("--odometry-cov-scale", o.odometry_covariance_scale,
                                   "multiply the file's odometry covariances")
                       ->capture_default_str()
                       ->check(PositiveNumber()));
  tuning.push_back(cmd->add_option("--odometry-noise", o.odometry_noise,
                                   "SRR,SRT,STR,STT: noise growing with each step's motion (m/m, "
                                   "m/rad, rad/m, rad/rad), added to the file's")
                       ->delimiter(',')
                       ->expected(4)
                       ->check(NonNegativeNumber()));
  tuning.push_back(cmd->add_option("--sighting-cov-scale", o.sighting_covariance_scale,
                                   "multiply the file's sighting covariances")
                       ->capture_default_str()
                       ->check(PositiveNumber()));
  tuning.push_back(cmd->add_option("--sighting-noise", o.sighting_noise,
                                   "RANGE_M,BEARING_DEG: a range-bearing sensor's noise in place "
                                   "of the file's sighting covariances")
                       ->delimiter(',')
                       ->expected(2)
                       ->check(PositiveNumber()));
  tuning.push_back(
      cmd->add_option("--gate-chi2", o.gate_chi2, "association gate (squared Mahalanobis)")
          ->capture_default_str()
          ->check(PositiveNumber()));
  tuning.push_back(cmd->add_option("--new-landmark-chi2", o.new_landmark_chi2,
                                   "distance beyond which a sighting starts a new landmark")
                       ->capture_default_str()
                       ->check(PositiveNumber()));
  return tuning;
}

}  // namespace

void RegisterRun(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd =
      app.add_subcommand("run", "EKF-SLAM or FastSLAM over a real data set (iSAM format)");
  AddExamples(cmd, {
               "--isam ../shared/datasets/victoria_park/victoria_park_isam.txt --config configs/victoria_park.yaml --out out/victoria_park",
               "--isam ../shared/datasets/victoria_park/victoria_park_isam.txt --config configs/victoria_park.yaml --filter fastslam2 --association nn --out out/victoria_park_fastslam2"});
  cmd->add_option("--isam", o->isam,
                  "iSAM-format log (ODOMETRY/LANDMARK lines), e.g. Victoria Park")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "output directory")->required();
  CLI::Option* association = AddAssociationOptions(cmd, *o);
  const std::vector<CLI::Option*> tuning = AddIsamTuningOptions(cmd, *o);
  cmd->add_option("--filter", o->filter,
                  "ekf, fastslam1 or fastslam2 (with --association nn or ml: per-particle "
                  "maximum likelihood)")
      ->check(CLI::IsMember({"ekf", "fastslam1", "fastslam2"}))
      ->capture_default_str();
  cmd->add_option("--particles", o->particles, "FastSLAM's particle count")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--seed", o->seed,
                  "FastSLAM's random seed (the same seed gives the same run at any thread count; "
                  "the EKF draws nothing)")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "FastSLAM's threads (0: all usable CPUs)")
      ->check(CLI::Range(0, 1024));
  CLI::Option* config =
      cmd->add_option("--config", o->config,
                      "the runner's parameters from a YAML file (configs/victoria_park.yaml); "
                      "--association overrides its association")
          ->check(CLI::ExistingFile);
  for (CLI::Option* option : tuning) config->excludes(option);
  cmd->add_flag("--no-figures", o->no_figures, "skip the PNG figure");
  cmd->callback([o, association, &exit_code] {
    o->association_given = association->count() > 0;
    exit_code = RunIsamCommand(*o);
  });
}

}  // namespace slamkit::app
