#include "slamkit/runners/grid/grid_config.hpp"

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace slamkit {
namespace {

using config::Bound;
using config::Param;
using config::ParamTable;

constexpr Bound kNonNeg = Bound::kNonNegative;
constexpr Bound kPos = Bound::kPositive;

// A kernel widened by more (11° of heading) searches hundreds of cells around each beam's end.
constexpr double kMaxSigmaPerM = 0.2;

void AddMatcher(const std::string& s, ScanMatcherParams& m, ParamTable& t) {
  using config::Flag;
  using config::Integer;
  using config::Number;
  MatchConstraintParams& c = m.constraints;
  const ParamTable lines = {
      Integer(s, "beam_stride", &m.beam_stride, 1, "match every k-th beam"),
      Integer(s, "search_cells", &m.search_cells, 0, "window half-width around each beam end"),
      Number(s, "score_sigma_m", &m.score_sigma_m, kPos, "m", "width of a beam's score"),
      config::AtMost(Number(s, "score_sigma_per_m", &m.score_sigma_per_m, kNonNeg, "",
                            "... widened by this times the beam's range (0: off)"),
                     kMaxSigmaPerM),
      Number(s, "likelihood_sigma_m", &m.likelihood_sigma_m, kPos, "m",
             "sigma of the per-beam Gaussian in the scan likelihood"),
      Number(s, "linear_step_m", &m.linear_step_m, kPos, "m", "initial hill-climbing step"),
      Number(s, "angular_step_rad", &m.angular_step_rad, kPos, "rad", "initial heading step"),
      Integer(s, "refinements", &m.refinements, 0, "how many times the steps are halved"),
      Number(s, "min_score_fraction", &m.min_score_fraction, kNonNeg, "",
             "accept a match only if its score is at least this times the beams matched"),
      config::AtMost(Number(s, "rescue_sigma_per_m", &m.rescue_sigma_per_m, kNonNeg, "",
                            "a rejected match is tried again with score_sigma_per_m this (0: off)"),
                     kMaxSigmaPerM),
      Number(s, "prior_sigma_xy_m", &m.prior_sigma_xy_m, kNonNeg, "m",
             "sigma of the translation prior around the guess (0: none)"),
      Number(s, "prior_sigma_theta_rad", &m.prior_sigma_theta_rad, kNonNeg, "rad",
             "sigma of the heading prior around the guess (0: none)"),
      Flag(s, "coarse_pass", &m.coarse_pass, "a wider pass first, to pull far guesses in"),
      Integer(s, "coarse_search_cells", &m.coarse_search_cells, 0, "the coarse pass's window"),
      Number(s, "coarse_score_sigma_m", &m.coarse_score_sigma_m, kPos, "m",
             "the coarse pass's score width"),
      Integer(s, "coarse_beam_stride", &m.coarse_beam_stride, 1, "the coarse pass's stride"),
      Integer(s, "coarse_refinements", &m.coarse_refinements, 0, "the coarse pass's halvings"),
      config::AtMost(Number(s, "coarse_score_sigma_per_m", &m.coarse_score_sigma_per_m, kNonNeg, "",
                            "the coarse pass's score_sigma_per_m"),
                     kMaxSigmaPerM),
      Number(s, "heading_sweep_rad", &m.heading_sweep_rad, kNonNeg, "rad",
             "sweep the coarse score over +- this before climbing (0: off)"),
      Number(s, "heading_sweep_step_rad", &m.heading_sweep_step_rad, kPos, "rad",
             "the sweep's step"),
      Number(s, "widen_below_score_fraction", &m.widen_below_score_fraction, kNonNeg, "",
             "retry a match scoring below this times the beams from other headings"),
      Number(s, "widen_heading_step_rad", &m.widen_heading_step_rad, kPos, "rad",
             "the retries' heading step"),
      Integer(s, "widen_heading_starts", &m.widen_heading_starts, 0, "retries on each side"),
      Number(s, "min_information_ratio", &c.min_information_ratio, kNonNeg, "",
             "keep the guess in directions with less information than this times the best"),
      Integer(s, "normal_neighbours", &c.normal_neighbours, 1,
              "beam-end normals fitted to the ends within this many beams"),
      Number(s, "normal_radius_m", &c.normal_radius_m, kPos, "m", "... and this distance"),
      Number(s, "max_normal_spread", &c.max_normal_spread, kNonNeg, "",
             "... that lie on a line (spread below this)"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddTop(RbpfGridSlamParams& p, ParamTable& t) {
  using config::Number;
  using config::WithFlag;
  const ParamTable lines = {
      config::AtMost(WithFlag(config::Integer("", "particles", &p.particles, 1, "particles"),
                              "--particles"),
                     10000),
      WithFlag(config::Seed("", "seed", &p.seed, "random seed of the filter"), "--seed"),
      WithFlag(Number("", "linear_update_m", &p.linear_update_m, kNonNeg, "m",
                      "update after driving this far"),
               "--linear-update"),
      WithFlag(Number("", "angular_update_rad", &p.angular_update_rad, kNonNeg, "rad",
                      "update after turning this far"),
               "--angular-update"),
      Number("resampling", "threshold", &p.resampling.threshold, kNonNeg, "",
             "resample when N_eff / N falls below this"),
      WithFlag(config::Choice("resampling", "scheme", &p.resampling.scheme,
                              {"systematic", "stratified", "multinomial"}, "resampling scheme"),
               "--resampling"),
      Number("", "likelihood_gain", &p.likelihood_gain, kPos, "",
             "log-likelihoods times this before normalising"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddMotion(RbpfGridSlamParams& p, ParamTable& t) {
  using config::Number;
  using config::WithFlag;
  OdometryNoiseParams& m = p.motion;
  const ParamTable lines = {
      WithFlag(Number("motion", "srr", &m.srr, kNonNeg, "m/m", "odometry noise: m per m driven"),
               "--srr"),
      WithFlag(Number("motion", "srt", &m.srt, kNonNeg, "m/rad",
                      "odometry noise: m per rad turned"),
               "--srt"),
      WithFlag(Number("motion", "str", &m.str, kNonNeg, "rad/m",
                      "odometry noise: rad per m driven"),
               "--str"),
      WithFlag(Number("motion", "stt", &m.stt, kNonNeg, "rad/rad",
                      "odometry noise: rad per rad turned"),
               "--stt"),
      Number("motion", "heading_drift_rad_per_m", &p.odometry_heading_drift_rad_per_m,
             Bound::kFinite, "rad/m", "odometry calibration: extra turn per metre driven"),
      config::Flag("motion", "estimate_heading_drift", &p.estimate_heading_drift,
                   "estimate the drift as the filter runs, the value above as its prior"),
      Number("motion", "heading_drift_prior_m2", &p.heading_drift_prior_m2, kPos, "m^2",
             "the prior's weight, in squared metres driven"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddMatching(RbpfGridSlamParams& p, ParamTable& t) {
  using config::Number;
  const ParamTable lines = {
      config::WithFlag(Number("", "usable_range_m", &p.usable_range_m, kPos, "m",
                              "laser range used: in the maps, the matching and the tracking"),
                       "--usable-range"),
      config::Flag("", "misses_spare_scan_hits", &p.misses_spare_scan_hits,
                   "a scan's free rays skip the cells its own returns hit"),
      config::Limit("", "no_return_ray_length_m", &p.no_return_ray_length_m, "m",
                    "free space marked by a no-return beam (null: the usable range)"),
      Number("", "widen_below_typical_score", &p.widen_below_typical_score, kNonNeg, "",
             "retry matches below this times the last mean score (0: off)"),
      config::Choice("", "proposal", &p.proposal, {"gaussian", "scan_match"},
                     "gaussian (Grisetti et al. 2007) or scan_match (ROS GMapping)"),
      config::AtMost(Number("", "sampled_start_fraction", &p.sampled_start_fraction, kNonNeg, "",
                            "particles whose match starts at a motion draw"),
                     1.0),
      Number("", "heading_sweep_sigmas", &p.heading_sweep_sigmas, kNonNeg, "",
             "prediction starts sweep their heading over this many heading sigmas"),
      Number("gaussian", "step_xy_m", &p.gaussian.step_xy_m, kPos, "m",
             "the fitted Gaussian's sampling step in x and y"),
      Number("gaussian", "step_theta_rad", &p.gaussian.step_theta_rad, kPos, "rad",
             "the fitted Gaussian's sampling step in heading"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
  AddMatcher("matcher", p.matcher, t);
}

void AddTracking(RbpfGridSlamParams& p, ParamTable& t) {
  using config::Number;
  using config::WithFlag;
  t.push_back(config::Choice("", "tracking_mode", &p.tracking_mode,
                             {"tracked_motion", "track_only", "off"},
                             "what the scans between updates do"));
  AddMatcher("tracking", p.tracking, t);
  for (Param& line : t) {
    if (line.section == "tracking" && line.key == "prior_sigma_xy_m") {
      line.flag = "--tracking-prior-xy";
      line.help = "tracking: sigma of the translation prior around the odometry guess (0: none)";
    }
  }
  const ParamTable lines = {
      WithFlag(Number("", "tracking_max_correction_m", &p.tracking_max_correction_m, kNonNeg,
                      "m", "tracking: largest translation correction accepted"),
               "--tracking-max-correction"),
      WithFlag(Number("", "tracking_max_correction_rad", &p.tracking_max_correction_rad, kNonNeg,
                      "rad", "tracking: largest heading correction accepted"),
               "--tracking-max-correction-angle"),
      config::Limit("", "tracking_max_step_m", &p.tracking_max_step_m, "m",
                    "a scan this far from the one before is an update (null: never)"),
      config::Limit("", "tracking_max_step_rad", &p.tracking_max_step_rad, "rad",
                    "a scan this far from the one before is an update (null: never)"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddGrid(OccupancyGridParams& g, ParamTable& t) {
  using config::Number;
  const ParamTable lines = {
      config::WithFlag(Number("grid", "resolution_m", &g.resolution_m, kPos, "m",
                              "map cell size"),
                       "--resolution"),
      Number("grid", "log_odds_hit", &g.log_odds_hit, Bound::kFinite, "", "log-odds of a hit"),
      Number("grid", "log_odds_miss", &g.log_odds_miss, Bound::kFinite, "", "of a miss"),
      Number("grid", "log_odds_min", &g.log_odds_min, Bound::kFinite, "", "a cell's lowest"),
      Number("grid", "log_odds_max", &g.log_odds_max, Bound::kFinite, "", "a cell's highest"),
      Number("grid", "max_extent_m", &g.max_extent_m, kPos, "m", "the largest map side"),
      config::Seed("grid", "max_cells", &g.max_cells, "the most cells a map may have"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddLoopGroups(LoopGroupParams& p, ParamTable& t) {
  using config::Integer;
  using config::Number;
  const std::string s = "graph.loop_groups";
  const ParamTable lines = {
      Integer(s, "min_size", &p.min_size, 0,
              "closures a group of agreeing ones needs to be tried against the loss (0: off)"),
      Integer(s, "max_node_gap", &p.max_node_gap, 1,
              "closures this many nodes apart or more start another group"),
      Number(s, "max_translation_m", &p.max_translation_m, kNonNeg, "m",
             "two closures agree when they place their nodes as the chain does to this ..."),
      Number(s, "max_rotation_rad", &p.max_rotation_rad, kNonNeg, "rad", "... and this"),
      Integer(s, "max_groups", &p.max_groups, 0, "groups tried per optimisation"),
      Number(s, "agreement_chi2", &p.agreement_chi2, kPos, "",
             "a closure agrees with a solution when its whitened squared residual is at most this"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddRefinement(const std::string& s, GridRefinementParams& p, ParamTable& t) {
  using config::Integer;
  using config::Number;
  const ParamTable lines = {
      Integer(s, "max_iterations", &p.max_iterations, 0,
              "least-squares iterations refining an accepted match on the interpolated map "
              "(0: not refined)"),
      Number(s, "occupied_space_weight", &p.occupied_space_weight, kNonNeg, "",
             "weight of the points' (1 - P) residuals, over sqrt(points)"),
      Number(s, "translation_weight", &p.translation_weight, kNonNeg, "1/m",
             "weight of the move from the match, per metre ..."),
      Number(s, "rotation_weight", &p.rotation_weight, kNonNeg, "1/rad", "... and per radian"),
      config::AtMost(Number(s, "unknown_probability", &p.unknown_probability, kNonNeg, "",
                            "the occupancy given to unobserved cells"),
                     1.0),
  };
  t.insert(t.end(), lines.begin(), lines.end());
}

void AddGraph(GraphGridSlamParams& g, ParamTable& t) {
  using config::Integer;
  using config::Number;
  const std::string s = "graph", l = "graph.loop";
  LoopClosureParams& c = g.loop;
  const ParamTable lines = {
      Number(s, "node_min_translation_m", &g.node_min_translation_m, kNonNeg, "m",
             "a scan is a node once the front end has moved this far from the last"),
      Number(s, "node_min_rotation_rad", &g.node_min_rotation_rad, kNonNeg, "rad",
             "... or turned this far"),
      Integer(s, "nodes_per_submap", &g.submaps.nodes_per_submap, 1,
              "a submap is started every this many nodes and holds twice as many"),
      Number(s, "sparse_step_m", &g.sparse_step_m, kNonNeg, "m",
             "a scan this far from the one before is sparse ..."),
      Number(s, "sparse_step_rad", &g.sparse_step_rad, kNonNeg, "rad", "... or turned this far"),
      Number(s, "sparse_heading_sweep_rad", &g.sparse_heading_sweep_rad, kNonNeg, "rad",
             "a sparse scan's match sweeps its heading over +- this ..."),
      Number(s, "sparse_widen_below_score_fraction", &g.sparse_widen_below_score_fraction,
             kNonNeg, "", "... and retries a climb scoring below this times its beams"),
      Number(s, "dense_max_correction_m", &g.dense_max_correction_m, kNonNeg, "m",
             "a dense scan's match moving the odometry guess further keeps the guess (0: off)"),
      Number(s, "local_sigma_xy_m", &g.local_sigma_xy_m, kPos, "m",
             "noise of the front end's motion between consecutive nodes"),
      Number(s, "local_sigma_theta_rad", &g.local_sigma_theta_rad, kPos, "rad", "... in heading"),
      config::Choice(s, "loop_loss", &g.loop_loss.kind, {"none", "huber", "cauchy", "dcs"},
                     "robust loss of loop closures"),
      Number(s, "loop_loss_scale", &g.loop_loss.scale, kPos, "", "its scale (whitened units)"),
      Integer(s, "optimize_every_nodes", &g.optimize_every_nodes, 1,
              "background search and optimisation every this many nodes"),
      Integer(s, "max_iterations", &g.max_iterations, 1, "iterations per optimisation"),
      Integer(s, "final_max_iterations", &g.final_max_iterations, 1, "... of the final one"),
      config::AtMost(Number(s, "false_closure_fraction", &g.false_closure_fraction, kNonNeg, "",
                            "robustness study: a false closure per accepted one with this "
                            "probability (0: none)"),
                     1.0),
      config::AtMost(Number(l, "min_score", &c.matcher.min_score, kNonNeg, "",
                            "a closure's correlative score (mean occupancy) at least this"),
                     1.0),
      config::AtMost(Integer(l, "branch_and_bound_depth", &c.matcher.branch_and_bound_depth, 1,
                             "precomputed grids of the branch and bound"),
                     16),
      Number(l, "base_linear_window_m", &c.base_linear_window_m, kNonNeg, "m",
             "search window +- this in x and y ..."),
      Number(l, "linear_window_growth", &c.linear_window_growth, kNonNeg, "m/m",
             "... plus this per metre driven since the node was last tied to the submap"),
      Number(l, "max_linear_window_m", &c.max_linear_window_m, kNonNeg, "m", "... at most this"),
      Number(l, "base_angular_window_rad", &c.base_angular_window_rad, kNonNeg, "rad",
             "search window +- this in heading ..."),
      Number(l, "angular_window_growth_rad_per_m", &c.angular_window_growth_rad_per_m, kNonNeg,
             "rad/m", "... plus this per metre driven"),
      Number(l, "max_angular_window_rad", &c.max_angular_window_rad, kNonNeg, "rad",
             "... at most this"),
      Number(l, "max_node_distance_m", &c.max_node_distance_m, kNonNeg, "m",
             "search a submap with a node within window + this"),
      Number(l, "max_point_range_m", &c.max_point_range_m, kPos, "m",
             "the branch and bound uses the points within this range"),
      Integer(l, "node_stride", &c.node_stride, 1, "search every k-th node"),
      config::Flag(l, "thin_wide_windows", &c.thin_wide_windows,
                   "a window k times the base one is searched on every k-th node"),
      Number(l, "sigma_xy_m", &c.sigma_xy_m, kPos, "m", "a closure's noise in x and y"),
      Number(l, "sigma_theta_rad", &c.sigma_theta_rad, kPos, "rad", "... in heading"),
  };
  t.insert(t.end(), lines.begin(), lines.end());
  AddMatcher("graph.matcher", g.matcher, t);
  AddMatcher("graph.loop.refinement", c.refinement, t);
  AddLoopGroups(g.loop_groups, t);
  AddRefinement("graph.refinement", g.refinement, t);
}

}  // namespace

config::ParamTable GridParamTable(GridSlamConfig& config) {
  RbpfGridSlamParams& p = config.rbpf;
  ParamTable t = {config::WithFlag(
      config::Choice("", "backend", &config.backend, GridBackendNames(),
                     "the grid SLAM: rbpf (particle filter) or graph (submaps and a pose graph)"),
      "--backend")};
  AddTop(p, t);
  AddMotion(p, t);
  AddMatching(p, t);
  AddTracking(p, t);
  AddGrid(p.grid, t);
  AddGraph(config.graph, t);
  return t;
}

GridSlamConfig LoadGridConfig(const std::filesystem::path& path, const GridSlamConfig& defaults) {
  const YAML::Node yaml = config::LoadYamlFile(path);
  GridSlamConfig config = defaults;
  const ParamTable table = GridParamTable(config);
  config::ReadParams(yaml, path.string(), table);
  const OccupancyGridParams& g = config.rbpf.grid;
  if (g.log_odds_min >= g.log_odds_max) {
    const config::Section root(yaml, path.string(), "", config::KnownKeys(table, ""));
    root.Child("grid", config::KnownKeys(table, "grid"))
        .Fail("log_odds_min", "must be below log_odds_max");
  }
  return config;
}

nlohmann::json GridParamsJson(const GridSlamConfig& config) {
  GridSlamConfig copy = config;
  return config::ParamsJson(GridParamTable(copy));
}

}  // namespace slamkit
