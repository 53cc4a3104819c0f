#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/laser_scan.hpp"
#include "slamkit/core/pose2.hpp"
#include "slamkit/filters/grid/grid_map_view.hpp"
#include "slamkit/filters/grid/match_constraints.hpp"
#include "slamkit/maps/occupancy_grid.hpp"

namespace slamkit {

struct ScanMatcherParams {
  int beam_stride = 1;             // match every k-th beam
  int search_cells = 1;            // window half-width around each beam end, in cells
  double score_sigma_m = 0.05;     // width of each beam's score exp(−d²/σ²)
  // A beam at range r scores with σ = hypot(score_sigma_m, score_sigma_per_m × r) and searches
  // a window of at least σ (in cells) around its end: a heading error moves a far end further
  // than a near one, so far returns still pull the heading when it is off (a heading σ in rad,
  // in effect). 0: every beam alike.
  double score_sigma_per_m = 0.0;
  double likelihood_sigma_m = 0.075;  // σ of the per-beam Gaussian in the scan likelihood
  double linear_step_m = 0.05;     // initial hill-climbing steps (halved when stuck)
  double angular_step_rad = 0.05;
  int refinements = 5;             // how many times the steps are halved
  double min_score_fraction = 0.15;  // accept a match only if score ≥ this × beams matched
  // An optional prior around the initial guess: the climb maximises score − (Δxy/σ_xy)² −
  // (Δθ/σ_θ)², so where the map leaves a direction unconstrained (along a corridor whose end is
  // not mapped yet) the guess holds instead of drifting. Zero switches a term off.
  double prior_sigma_xy_m = 0.0;
  double prior_sigma_theta_rad = 0.0;
  // A coarse pass runs first, with a wider window and score, on every `coarse_beam_stride`-th
  // beam: it pulls guesses that are several cells off into the fine pass's reach. Guesses that
  // are known to be close (tracking between filter updates) can skip it.
  bool coarse_pass = true;
  int coarse_search_cells = 3;
  double coarse_score_sigma_m = 0.15;
  int coarse_beam_stride = 3;
  int coarse_refinements = 5;
  double coarse_score_sigma_per_m = 0.0;  // the coarse pass's score_sigma_per_m
  // Before the coarse pass, the coarse score is swept over headings initial ± k·step within this
  // half-width, and the climb starts from the best (the initial heading on ties): a turn that
  // odometry misjudged by more than the climb can recover (CSAIL's odometry is 12° off on one
  // step in ten) is found at the cost of one score per heading. Zero switches it off.
  double heading_sweep_rad = 0.0;
  double heading_sweep_step_rad = 0.02;
  // A match scoring below this fraction of its beams is retried from headings
  // ±k·widen_heading_step_rad (k = 1..widen_heading_starts) around the guess, and the best climb
  // kept: a turn that odometry misjudged by more than the climb can recover leaves the first
  // climb in a poor local optimum. Zero switches it off.
  double widen_below_score_fraction = 0.0;
  double widen_heading_step_rad = 0.06;
  int widen_heading_starts = 2;
  // A match that is not accepted is tried again with both passes' kernels widened by this
  // times each beam's range (score_sigma_per_m); if that one is accepted, the fine climb with
  // these params refines it (a wide kernel is biased by a few centimetres) and the result is
  // accepted. Where few returns are near (open ground, a hall), a heading error puts the far
  // ends outside every window and the plain match fails. 0: no second try.
  double rescue_sigma_per_m = 0.0;
  // Where the scan does not constrain the pose (a featureless corridor), the match keeps the
  // initial guess in that direction (see MatchConstraintParams).
  MatchConstraintParams constraints;
};

// The beams of one scan that can be matched, as points in the robot frame (the laser offset
// already applied), with the unit direction of each beam (for the free-space test) and the
// surface normal at its end (zero where there is none; fitted to all the scan's returns).
struct ScanPoints {
  std::vector<Eigen::Vector2d> ends;
  std::vector<Eigen::Vector2d> directions;
  std::vector<Eigen::Vector2d> normals;
};

// Every params.beam_stride-th beam that returned within `usable_range_m` (the laser's usable
// range: the same one the map insertion cuts beams at).
ScanPoints PrepareScan(const LaserScan& scan, double usable_range_m,
                       const ScanMatcherParams& params);

struct MatchQuality {
  double score = 0.0;           // Σ exp(−d²/σ²) over beams (larger is better)
  double log_likelihood = 0.0;  // Σ log N(d; 0, σ_l) over beams, up to a constant
  int matched = 0;              // beams that found an occupied cell in their window
};

// Evaluates `points` at robot pose `pose` against the map `grid` (a view: the map, and a second
// layer where it is unknown): each beam end looks for the nearest occupied cell in a small
// window whose neighbour toward the sensor is free (GMapping's test), and d is the distance from
// the end to that cell's centre. A view without a second layer reads the map's tiles directly.
// With `hits`, hits[i] says whether beam i found an occupied cell.
MatchQuality EvaluatePose(const GridMapView& grid, const ScanPoints& points, const Pose2& pose,
                          const ScanMatcherParams& params,
                          std::vector<std::uint8_t>* hits = nullptr);

// EvaluatePose(...) when its score can exceed `min_score`; nullopt once the beams left cannot
// lift the score above it (each adds at most 1), so a search comparing candidates with the best
// so far stops scoring a hopeless one early and takes the same decisions.
std::optional<MatchQuality> EvaluatePoseAbove(const GridMapView& grid, const ScanPoints& points,
                                              const Pose2& pose, const ScanMatcherParams& params,
                                              double min_score);

// EvaluatePose(...).log_likelihood without the score's exp per beam: the proposal and the
// weights need only the likelihood.
double ScanLogLikelihood(const GridMapView& grid, const ScanPoints& points, const Pose2& pose,
                         const ScanMatcherParams& params);

struct MatchResult {
  Pose2 pose;
  MatchQuality quality;
  bool accepted = false;  // the score passed min_score_fraction
  MatchConstraints constraints;  // the directions in which the guess was kept
  bool rescued = false;  // accepted only after the rescue (ScanMatcherParams::rescue_sigma_per_m)
};

// Hill climbing from `initial` on the score, with six moves (±x, ±y, ±θ) and step halving;
// a coarse pass first, then the fine one from its result; then, in the directions the matched
// beams leave unconstrained, the pose moves back to the guess (MatchConstraintParams); then,
// if not accepted, the rescue (rescue_sigma_per_m).
MatchResult MatchScan(const GridMapView& grid, const ScanPoints& points, const Pose2& initial,
                      const ScanMatcherParams& params);

}  // namespace slamkit
