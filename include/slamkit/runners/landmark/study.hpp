#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "slamkit/eval/spread.hpp"
#include "slamkit/runners/landmark/active_monte_carlo.hpp"
#include "slamkit/runners/landmark/filter_choice.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

namespace slamkit {

// SPEC S2's experiment (seed 001 Sec. 4): EKF-SLAM on the route, FastSLAM on the route and
// SWSLAM (EKF-SLAM with self-detected waypoints), each over the same Monte Carlo runs: run k of
// every method has the same world, the same noise and observation-order streams and so, on the
// route, the same true path.

struct StudyParams {
  int runs = 50;  // seed 001: 50 Monte Carlo runs per method. >= 1.
  std::uint64_t seed = 1;
  int threads = 0;  // 0: all the CPUs this process may use
  // The FastSLAM on the route (SPEC S2: the standard FastSLAM, 1.0 or 2.0) and its particles.
  FilterKind fastslam = FilterKind::kFastSlam2;
  int particles = 100;  // >= 1
  // Called with (method index in StudyResult::methods, finished, total): with 0 finished when the
  // method starts, then as its runs finish, from worker threads one at a time. The methods run
  // one after the other.
  std::function<void(int, int, int)> progress;
};

// A figure as seed 001's Tables 4 and 5 give it: the mean over runs of each run's RMS error and
// its variance over runs.
struct MeanVariance {
  double mean = 0.0;
  double variance = 0.0;
};

struct StudyMethodResult {
  std::string key;    // "ekf_slam", "fastslam", "swslam": file and JSON names
  std::string title;  // "EKF-SLAM", "FastSLAM 2.0" (or 1.0), "SWSLAM": tables and legends
  FilterKind filter = FilterKind::kEkf;
  PlannerKind planner = PlannerKind::kRoute;
  // Per-step series over the runs still running, run 0, and every run's summary.
  MonteCarloResult mc;
  std::vector<ActiveRunTrace> traces;  // one per run (period states dropped)
  std::vector<SectionMean> sections;   // seed 001 Tables 1-3, one entry per section
  Spread position_rms_m;               // Table 4: each run's RMS over the runs
  Spread heading_rms_rad;              // Table 5
  // The median over runs of each run's mean NEES: one diverging run (a wrong association in a
  // dense cluster) dominates the ANEES, not this.
  double anees_run_median = 0.0;
  double wall_time_s = 0.0;  // the method's whole Monte Carlo set
};

struct StudyResult {
  StudyParams params;
  std::vector<StudyMethodResult> methods;  // the seed's order: EKF-SLAM, FastSLAM, SWSLAM
};

// The three methods in indexes 0-2 (as StudyParams::progress names them); SWSLAM's set runs
// first, as the route methods are measured on its sections: route run k on the sections SWSLAM's
// run k detected, carried onto the route (CarrySections), so that Tables 1-3 set the same
// stretches of the route beside each other. Throws InputError for runs or particles < 1 or a
// `fastslam` that is not FastSLAM.
StudyResult RunStudy(const ScenarioConfig& config, const StudyParams& params);

// The title of method `index` (0-2) in StudyResult::methods, before the study runs.
std::string StudyMethodTitle(int index, const StudyParams& params);

// How RunStudy delimits and averages the sections, in a sentence or four for the outputs.
std::string_view StudySectionsNote();

// Seed 001's own figures (Tables 1-5, as the paper prints them), to set ours beside: the paper's,
// not ours. Its Table 4 labels position errors "rad" and "rad²", evidently metres.
struct PaperSectionRow {
  int observations;               // "total number of observed landmarks"
  int observations_per_period;    // "average number of one-step observed landmarks"
  int observations_per_landmark;  // "observed frequency of single landmark"
};
struct PaperMethodFigures {
  std::string_view key;  // as StudyMethodResult::key
  std::array<PaperSectionRow, 3> sections;
  MeanVariance position_m;   // Table 4
  MeanVariance heading_rad;  // Table 5
};
const std::array<PaperMethodFigures, 3>& Seed001Figures();
// The entry of Seed001Figures() with `key`; std::invalid_argument if there is none.
const PaperMethodFigures& Seed001FiguresOf(std::string_view key);

}  // namespace slamkit
