#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "slamkit/eval/consistency.hpp"
#include "slamkit/runners/cooperative/coop_config.hpp"
#include "slamkit/runners/cooperative/coop_run.hpp"

namespace slamkit {

// One vehicle under one mode over the runs.
struct CoopVehicleSummary {
  double position_rmse_m = 0.0;  // √ of the mean over runs of each run's RMS²
  double heading_rmse_rad = 0.0;
  double position_aligned_rmse_m = -1.0;  // as position_rmse_m, over the runs that have one
  double anees = 0.0;            // the mean over runs and records of the pose NEES
  double anees_in_band = 0.0;    // share of the records whose mean over runs is in `band`
  double map_rmse_m = -1.0;      // mean over the runs that have one
  double landmarks = 0.0;        // mean size of the vehicle's map
  double association_agreement = -1.0;  // mean over the runs that have one (CoopVehicleTrace)
  std::vector<double> t_s;                // the records' times (run 0's)
  std::vector<double> position_cov_norm;  // per record, the mean over runs of ‖C_pp‖
  std::vector<double> anees_per_record;
  // Against Mono on the same runs (empty when Mono did not run): SPEC S3's IR per record from
  // the mean covariance norms, in %, its mean over the records and its last value.
  std::vector<double> improvement_ratio_pct;
  double improvement_ratio_mean_pct = 0.0;
  double improvement_ratio_final_pct = 0.0;
};

struct CoopModeSummary {
  CoopMode mode = CoopMode::kMono;
  std::vector<CoopVehicleSummary> vehicles;
  ChiSquareBand band;            // of a mean over `runs` NEES of 3 dof
  double update_time_mean_s = 0.0;
  CooperativeEkfSlam::Counts counts;  // run 0's
  CoopModeResult first_run;           // for the figures and the per-vehicle files
};

struct CoopStudyResult {
  int runs = 0;
  std::vector<CoopModeSummary> modes;
  LandmarkWorld landmarks;  // run 0's true landmarks (the figures'); empty when not known
  double wall_time_s = 0.0;
};

// Called after each run (1-based count, total), from one thread.
using CoopProgress = std::function<void(int done, int total)>;

// Every mode on the same `runs` simulated fleets of `config` (run r draws vehicle v's noise
// from Rng::ForStream(config.seed, r · vehicles + v), its messages' loss from seed + r), run in
// parallel on `threads` threads (0: all the CPUs this process may use) with the same figures for
// any thread count. Throws InputError for a config without vehicles.
CoopStudyResult RunCoopStudy(const CoopConfig& config, const std::vector<CoopMode>& modes,
                             const CoopProgress& progress = {}, int threads = 0);

// Every mode once on a recorded fleet (a data set); `true_ids` as RunCoopMode's.
CoopStudyResult RunCoopLog(const FleetLog& log, const FleetTruth& truth,
                           const std::vector<LandmarkId>& true_ids, const CoopFilterParams& params,
                           const std::vector<CoopMode>& modes, std::uint64_t seed);

// DIR/metrics.json (`params`, `command`, per mode its vehicles' figures) and DIR/MODE/ per mode:
// trajectory_K.tum and map_K.csv per vehicle and cov_norm.csv (t and ‖C_pp‖ of each vehicle),
// each written atomically. The figures are the command line's (report).
void WriteCoopOutputs(const std::filesystem::path& dir, const CoopStudyResult& result,
                      const nlohmann::json& params, const std::string& command);
nlohmann::json CoopMetricsJson(const CoopStudyResult& result);

}  // namespace slamkit
