// SPEC S3's experiments: every estimator on the same fleets, summarised over the runs.
#include "slamkit/runners/cooperative/coop_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "../common/ordered_batches.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit {
namespace {

struct VehicleSums {
  double position_sq = 0.0, heading_sq = 0.0, nees = 0.0, map = 0.0, landmarks = 0.0;
  double agreement = 0.0, aligned_sq = 0.0;
  int maps = 0, nees_runs = 0, agreements = 0, aligned = 0;
  std::vector<double> cov_norm, nees_per_record;
  std::vector<int> nees_count;  // per record, the runs where it is defined
};

void Accumulate(const CoopVehicleTrace& trace, VehicleSums* s) {
  s->position_sq += trace.position_rmse_m * trace.position_rmse_m;
  s->heading_sq += trace.heading_rmse_rad * trace.heading_rmse_rad;
  if (trace.position_aligned_rmse_m >= 0.0) {
    s->aligned_sq += trace.position_aligned_rmse_m * trace.position_aligned_rmse_m;
    ++s->aligned;
  }
  if (std::isfinite(trace.mean_nees)) {
    s->nees += trace.mean_nees;
    ++s->nees_runs;
  }
  s->landmarks += static_cast<double>(trace.map.landmarks.size());
  if (trace.map_rmse_m >= 0.0) {
    s->map += trace.map_rmse_m;
    ++s->maps;
  }
  if (trace.association_agreement >= 0.0) {
    s->agreement += trace.association_agreement;
    ++s->agreements;
  }
  const std::size_t n = s->cov_norm.empty() ? trace.position_cov_norm.size()
                                            : std::min(s->cov_norm.size(), trace.nees.size());
  s->cov_norm.resize(n, 0.0);
  s->nees_per_record.resize(n, 0.0);
  s->nees_count.resize(n, 0);
  for (std::size_t k = 0; k < n; ++k) {
    s->cov_norm[k] += trace.position_cov_norm[k];
    if (!std::isfinite(trace.nees[k])) continue;
    s->nees_per_record[k] += trace.nees[k];
    ++s->nees_count[k];
  }
}

CoopVehicleSummary Summary(const VehicleSums& s, int runs, const ChiSquareBand& band,
                           const CoopVehicleTrace& first) {
  CoopVehicleSummary v;
  v.position_rmse_m = std::sqrt(s.position_sq / runs);
  v.heading_rmse_rad = std::sqrt(s.heading_sq / runs);
  v.position_aligned_rmse_m = s.aligned > 0 ? std::sqrt(s.aligned_sq / s.aligned) : -1.0;
  v.anees = s.nees_runs > 0 ? s.nees / s.nees_runs : std::numeric_limits<double>::quiet_NaN();
  v.map_rmse_m = s.maps > 0 ? s.map / s.maps : -1.0;
  v.landmarks = s.landmarks / runs;
  v.association_agreement = s.agreements > 0 ? s.agreement / s.agreements : -1.0;
  // The band is that of a mean over all the runs: records where fewer have a NEES are left out.
  int inside = 0, counted = 0;
  for (std::size_t k = 0; k < s.cov_norm.size(); ++k) {
    v.t_s.push_back(first.estimate[k].t_s);
    v.position_cov_norm.push_back(s.cov_norm[k] / runs);
    const bool all = s.nees_count[k] == runs;
    v.anees_per_record.push_back(all ? s.nees_per_record[k] / runs
                                     : std::numeric_limits<double>::quiet_NaN());
    if (!all) continue;
    ++counted;
    inside += band.Contains(v.anees_per_record.back()) ? 1 : 0;
  }
  if (counted > 0) v.anees_in_band = double(inside) / double(counted);
  return v;
}

// IR of every mode against Mono's mean covariance norms, when Mono ran.
void AddImprovementRatios(CoopStudyResult* r) {
  const auto mono = std::find_if(r->modes.begin(), r->modes.end(),
                                 [](const CoopModeSummary& m) { return m.mode == CoopMode::kMono; });
  if (mono == r->modes.end()) return;
  for (CoopModeSummary& m : r->modes) {
    if (m.mode == CoopMode::kMono || !HasCovariance(m.mode)) continue;
    for (std::size_t v = 0; v < m.vehicles.size(); ++v) {
      CoopVehicleSummary& s = m.vehicles[v];
      const CoopVehicleSummary& base = mono->vehicles[v];
      s.improvement_ratio_pct =
          ImprovementRatio(base.t_s, base.position_cov_norm, s.t_s, s.position_cov_norm);
      const std::size_t n = s.improvement_ratio_pct.size();
      double sum = 0.0;
      for (double ir : s.improvement_ratio_pct) sum += ir;
      if (n == 0) continue;
      s.improvement_ratio_mean_pct = sum / double(n);
      s.improvement_ratio_final_pct = s.improvement_ratio_pct.back();
    }
  }
}

struct Fleet {
  FleetLog log;
  FleetTruth truth;
  std::vector<LandmarkId> ids;
};

// Every mode on run r's fleet (and, for run 0 only, its world: the figures draw it).
struct RunOutputs {
  std::vector<CoopModeResult> modes;
  LandmarkWorld world;
};

// The runs, in parallel batches (`fleet_of(r)` gives run r's fleet; every mode runs on it),
// summed in run order: the same figures for any thread count.
template <typename RunFleet>
CoopStudyResult Study(int runs, int vehicles, const std::vector<CoopMode>& modes,
                      const CoopFilterParams& params, std::uint64_t seed, RunFleet fleet_of,
                      const CoopProgress& progress, int threads) {
  const auto start = std::chrono::steady_clock::now();
  CoopStudyResult result;
  result.runs = runs;
  std::vector<std::vector<VehicleSums>> sums(modes.size(), std::vector<VehicleSums>(vehicles));
  std::vector<double> update_s(modes.size(), 0.0);
  result.modes.resize(modes.size());
  const auto run_one = [&](int r) {
    const Fleet fleet = fleet_of(r);
    RunOutputs out;
    if (r == 0) out.world = fleet.truth.world;
    for (const CoopMode mode : modes) {
      out.modes.push_back(RunCoopMode(fleet.log, fleet.truth, fleet.ids, mode, params, seed + r));
    }
    return out;
  };
  const auto take = [&](int r, RunOutputs&& out) {
    if (r == 0) result.landmarks = std::move(out.world);
    for (std::size_t m = 0; m < modes.size(); ++m) {
      for (int v = 0; v < vehicles; ++v) Accumulate(out.modes[m].vehicles[v], &sums[m][v]);
      update_s[m] += out.modes[m].update_time_mean_s;
      if (r == 0) result.modes[m].first_run = std::move(out.modes[m]);
    }
  };
  RunInOrderedBatches<RunOutputs>({runs, 16, threads, progress}, run_one, take);
  for (std::size_t m = 0; m < modes.size(); ++m) {
    CoopModeSummary& s = result.modes[m];
    s.mode = modes[m];
    s.band = AneesBand(runs, 3);
    s.update_time_mean_s = update_s[m] / runs;
    s.counts = s.first_run.counts;
    for (int v = 0; v < vehicles; ++v) {
      s.vehicles.push_back(Summary(sums[m][v], runs, s.band, s.first_run.vehicles[v]));
    }
  }
  AddImprovementRatios(&result);
  result.wall_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace

CoopStudyResult RunCoopStudy(const CoopConfig& config, const std::vector<CoopMode>& modes,
                             const CoopProgress& progress, int threads) {
  const int vehicles = static_cast<int>(config.scenario.vehicles.size());
  if (vehicles == 0) throw InputError("coop: the config has no vehicles to simulate");
  const LandmarkWorld world = MakeWorld(config.scenario.world);
  const auto fleet_of = [&](int r) {
    std::vector<Rng> noise;
    for (int v = 0; v < vehicles; ++v) {
      noise.push_back(Rng::ForStream(config.seed, std::uint64_t(r) * vehicles + v));
    }
    FleetRun run = SimulateFleet(config.scenario, world, noise);
    return Fleet{std::move(run.log), std::move(run.truth), std::move(run.landmark_ids)};
  };
  return Study(config.runs, vehicles, modes, config.filter, config.seed, fleet_of, progress,
               threads);
}

CoopStudyResult RunCoopLog(const FleetLog& log, const FleetTruth& truth,
                           const std::vector<LandmarkId>& true_ids, const CoopFilterParams& params,
                           const std::vector<CoopMode>& modes, std::uint64_t seed) {
  const auto fleet_of = [&](int) { return Fleet{log, truth, true_ids}; };
  return Study(1, log.vehicles, modes, params, seed, fleet_of, {}, 1);
}

}  // namespace slamkit
