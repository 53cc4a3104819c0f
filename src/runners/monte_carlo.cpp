#include "slamkit/runners/monte_carlo.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <mutex>
#include <thread>
#include <unordered_map>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "slamkit/eval/alignment.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

using Clock = std::chrono::steady_clock;

// Landmark error after the best rigid alignment of the estimated map onto the true one, pairing
// each estimated landmark with the true landmark of the sighting that created it.
double AlignedMapRmse(const LandmarkMap& map, const LandmarkWorld& world) {
  std::unordered_map<LandmarkId, Eigen::Vector2d> truth;
  for (const Landmark& l : world.landmarks) truth.emplace(l.id, l.position_m);
  std::vector<Eigen::Vector2d> from, to;
  for (const MappedLandmark& m : map.landmarks) {
    const auto it = truth.find(m.source_id);
    if (it == truth.end()) continue;
    from.push_back(m.position_m);
    to.push_back(it->second);
  }
  return AlignPoints(from, to).rmse_m;
}

AssociationOutcome OutcomeOf(AssociationDecision::Kind kind) {
  switch (kind) {
    case AssociationDecision::Kind::kMatched: return AssociationOutcome::kMatched;
    case AssociationDecision::Kind::kNew: return AssociationOutcome::kNew;
    case AssociationDecision::Kind::kDropped: break;
  }
  return AssociationOutcome::kDropped;
}

void ScoreDecisions(const EkfSlam& slam, const std::vector<PointObservation>& observations,
                    const std::vector<AssociationDecision>& decisions, AssociationScorer& scorer) {
  for (std::size_t i = 0; i < decisions.size(); ++i) {
    const AssociationDecision& d = decisions[i];
    const LandmarkId matched =
        d.kind == AssociationDecision::Kind::kMatched ? slam.LandmarkSourceId(d.landmark)
                                                      : kNoLandmark;
    scorer.Add(observations[i].id, OutcomeOf(d.kind), matched);
  }
}

}  // namespace

RunResult RunEkfSlamOnce(const ScenarioConfig& config, const LandmarkWorld& world, Rng& rng) {
  const ScenarioParams& scenario = config.scenario;
  const SimRun sim = Simulate(scenario, world, rng);
  EkfSlam slam(config.ekf, MakeMotionModel(scenario.vehicle),
               std::make_unique<RangeBearingModel>(scenario.sensor));
  slam.Reset(sim.initial_pose);
  RunResult out;
  AssociationScorer scorer;
  ScoreDecisions(slam, sim.initial_observations, slam.Update(sim.initial_observations), scorer);
  out.truth.push_back({0.0, sim.initial_pose});
  out.estimate.push_back({0.0, slam.pose()});
  for (const SimStep& step : sim.steps) {
    const auto start = Clock::now();
    slam.Predict(step.control, scenario.dt_s);
    const auto decisions = slam.Update(step.observations);
    out.step_time_s.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    ScoreDecisions(slam, step.observations, decisions, scorer);
    const Eigen::Vector3d e = PoseError(slam.pose(), step.true_pose);
    out.errors.push_back(e);
    out.nees.push_back(Nees(e, slam.PoseCovariance()));
    out.truth.push_back({step.t_s, step.true_pose});
    out.estimate.push_back({step.t_s, slam.pose()});
  }
  out.map = slam.Map();
  out.rmse = ComputePoseRmse(out.errors);
  out.map_rmse_m = AlignedMapRmse(out.map, world);
  out.association = scorer.score();
  return out;
}

namespace {

void AddScore(AssociationScore& total, const AssociationScore& s) {
  total.sightings += s.sightings;
  total.matched += s.matched;
  total.correct += s.correct;
  total.matchable += s.matchable;
  total.created += s.created;
  total.dropped += s.dropped;
}

// Per-step means over runs, then the summary figures; runs are visited in index order so the
// sums do not depend on which thread finished first.
void Aggregate(MonteCarloResult& mc) {
  const std::size_t steps = mc.runs.front().nees.size();
  const double runs = static_cast<double>(mc.runs.size());
  mc.anees.assign(steps, 0.0);
  mc.position_rmse_m.assign(steps, 0.0);
  mc.heading_rmse_rad.assign(steps, 0.0);
  double pos_sq = 0.0, head_sq = 0.0, time_sum = 0.0, mapped = 0.0;
  std::size_t time_count = 0;
  for (const RunResult& r : mc.runs) {
    for (std::size_t k = 0; k < steps; ++k) {
      mc.anees[k] += r.nees[k] / runs;
      mc.position_rmse_m[k] += r.errors[k].head<2>().squaredNorm() / runs;
      mc.heading_rmse_rad[k] += r.errors[k].z() * r.errors[k].z() / runs;
    }
    pos_sq += r.rmse.position_m * r.rmse.position_m;
    head_sq += r.rmse.heading_rad * r.rmse.heading_rad;
    for (double t : r.step_time_s) {
      time_sum += t;
      mc.step_time_max_s = std::max(mc.step_time_max_s, t);
    }
    time_count += r.step_time_s.size();
    mapped += static_cast<double>(r.map.landmarks.size());
    AddScore(mc.association, r.association);
  }
  int inside = 0;
  for (std::size_t k = 0; k < steps; ++k) {
    mc.position_rmse_m[k] = std::sqrt(mc.position_rmse_m[k]);
    mc.heading_rmse_rad[k] = std::sqrt(mc.heading_rmse_rad[k]);
    mc.anees_mean += mc.anees[k] / static_cast<double>(steps);
    inside += mc.band.Contains(mc.anees[k]) ? 1 : 0;
  }
  mc.anees_fraction_in_band = steps > 0 ? double(inside) / double(steps) : 0.0;
  mc.rmse = {std::sqrt(pos_sq / runs), std::sqrt(head_sq / runs)};
  mc.landmarks_mapped_mean = mapped / runs;
  mc.step_time_mean_s = time_count > 0 ? time_sum / double(time_count) : 0.0;
}

}  // namespace

MonteCarloResult RunMonteCarlo(const ScenarioConfig& config, const MonteCarloParams& params) {
  const ScenarioParams& scenario = config.scenario;
  if (params.runs < 1) throw std::invalid_argument("RunMonteCarlo: runs must be >= 1");
  MonteCarloResult mc;
  mc.world = MakeWorld(scenario.world);
  mc.runs.resize(params.runs);
  mc.band = AneesBand(params.runs, 3);
  const int threads = params.threads > 0 ? params.threads
                                         : static_cast<int>(std::thread::hardware_concurrency());
  std::mutex progress_mutex;
  int finished = 0;
  tbb::task_arena arena(std::max(threads, 1));
  arena.execute([&] {
    tbb::parallel_for(0, params.runs, [&](int k) {
      Rng rng = Rng::ForStream(params.seed, static_cast<std::uint64_t>(k));
      mc.runs[k] = RunEkfSlamOnce(config, mc.world, rng);
      const std::lock_guard lock(progress_mutex);
      ++finished;
      if (params.progress) params.progress(finished, params.runs);
    });
  });
  const Trajectory& truth = mc.runs.front().truth;
  for (std::size_t i = 1; i < truth.size(); ++i) mc.t_s.push_back(truth[i].t_s);  // [0]: start
  Aggregate(mc);
  return mc;
}

}  // namespace slamkit
