// `slamkit run`: EKF-SLAM over a real data set.
#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "commands.hpp"
#include "grid_common.hpp"
#include "slamkit/runners/outputs.hpp"
#include "slamkit/io/isam_reader.hpp"
#include "slamkit/report/figures.hpp"

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
  bool no_figures = false;
};

const char* AssociationName(AssociationMethod m) {
  switch (m) {
    case AssociationMethod::kKnown: return "known";
    case AssociationMethod::kJointCompatibility: return "joint-compatibility";
    case AssociationMethod::kNearestNeighbour: break;
  }
  return "nearest-neighbour";
}

int RunIsamCommand(const RunOptions& o) {
  const IsamLog log = ReadIsamLog(o.isam);
  OutputDir output(o.out);
  IsamRunParams params;
  params.ekf.association_method = o.known_association ? AssociationMethod::kKnown : o.association;
  params.ekf.jcbb.max_joint_tests = o.jcbb_max_joint_tests;
  params.ekf.association.gate_chi2 = o.gate_chi2;
  params.ekf.association.new_landmark_chi2 = o.new_landmark_chi2;
  params.odometry_covariance_scale = o.odometry_covariance_scale;
  params.sighting_covariance_scale = o.sighting_covariance_scale;
  const IsamRunResult result = RunEkfSlamOnIsam(log, params);
  const std::filesystem::path& dir = output.staging();
  if (!o.no_figures) {
    PathFigureData figure;
    figure.title = fmt::format("{} ({} association)", std::filesystem::path(o.isam).filename().string(),
                               AssociationName(params.ekf.association_method));
    figure.estimate = result.estimate;
    figure.map = result.map;
    WritePathFigure(dir / "map.png", figure);
  }
  WriteIsamOutputs(dir, IsamMetrics(result, params), result);  // metrics.json last
  output.Commit();
  fmt::print("{}: {} poses, {} sightings, {} association\n", o.isam, result.estimate.size(),
             result.sightings, AssociationName(params.ekf.association_method));
  fmt::print("  {:<28}{:>12}\n", "landmarks mapped", result.map.landmarks.size());
  fmt::print("  {:<28}{:>12}\n", "sightings dropped", result.dropped);
  fmt::print("  {:<28}{:>12.4f}\n", "association agreement", result.association_agreement);
  fmt::print("  {:<28}{:>12.3f}\n", "wall time [s]", result.wall_time_s);
  fmt::print("wrote {}\n", o.out);
  return 0;
}

}  // namespace

void RegisterRun(CLI::App& app, int& exit_code) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "EKF-SLAM over a real data set");
  cmd->add_option("--isam", o->isam,
                  "iSAM-format log (ODOMETRY/LANDMARK lines), e.g. Victoria Park")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--out", o->out, "output directory")->required();
  cmd->add_option("--association", o->association,
                  "nn (nearest neighbour), jcbb (joint compatibility, Neira & Tardos 2001) or "
                  "known (the file's landmark ids)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, AssociationMethod>{
          {"nn", AssociationMethod::kNearestNeighbour},
          {"jcbb", AssociationMethod::kJointCompatibility},
          {"known", AssociationMethod::kKnown}}))
      ->default_str("nn");
  cmd->add_flag("--known-association", o->known_association, "the same as --association known")
      ->excludes("--association");
  cmd->add_option("--jcbb-max-tests", o->jcbb_max_joint_tests,
                  "jcbb: most joint-compatibility tests per scan before taking the best found")
      ->capture_default_str()
      ->check(NonNegativeNumber());
  cmd->add_option("--odometry-cov-scale", o->odometry_covariance_scale,
                  "multiply the file's odometry covariances")
      ->capture_default_str()
      ->check(PositiveNumber());
  cmd->add_option("--sighting-cov-scale", o->sighting_covariance_scale,
                  "multiply the file's sighting covariances")
      ->capture_default_str()
      ->check(PositiveNumber());
  cmd->add_option("--gate-chi2", o->gate_chi2, "association gate (squared Mahalanobis)")
      ->capture_default_str()
      ->check(PositiveNumber());
  cmd->add_option("--new-landmark-chi2", o->new_landmark_chi2,
                  "distance beyond which a sighting starts a new landmark")
      ->capture_default_str()
      ->check(PositiveNumber());
  cmd->add_flag("--no-figures", o->no_figures, "skip the PNG figure");
  cmd->callback([o, &exit_code] { exit_code = RunIsamCommand(*o); });
}

}  // namespace slamkit::app
