// One correction step (selection, the sequential updates, the covariance downdate) of each
// selection policy of SPEC S1 on a filter of N landmarks with 10 matched sightings. Each
// iteration also times SelectAll on the same state, so `vs_all` is the ratio of the policy's time
// to the plain sequential EKF's measured in the same run. One thread.

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/filters/selection/selection.hpp"
#include "slamkit/filters/selection/selection_policies.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

constexpr std::uint64_t kSelectionBenchSeed = 20240611;
constexpr int kMatched = 10;  // sightings per step, unless a benchmark varies them

// A filter at the origin holding `landmarks` landmarks 1–30 m away in every direction, after a
// few odometry steps (so that the blocks are correlated), and fresh sightings of `matched` of them.
struct MappedFilter {
  MappedFilter(int landmarks, int matched)
      : ekf(3 + 2 * landmarks), kind(ekf.RegisterKind({2, {}, false})), model(sensor, kind, 5.0) {
    Rng rng(kSelectionBenchSeed);
    ekf.AddBlock(kPoseKind, Pose2().vector(), Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal());
    const Eigen::Matrix2d R = sensor.NoiseCovariance();
    const OdometryModel odometry;
    for (int i = 0; i < landmarks; ++i) {
      const double range = rng.Uniform(1.0, 30.0);
      const Eigen::Vector2d z(range, rng.Uniform(-std::numbers::pi, std::numbers::pi));
      const int observers[] = {kPoseKind};
      blocks.push_back(AugmentFrom(model, ekf, observers, z, R));
      if (i % (landmarks / 5) == 0) {
        Control u(3);
        u << 0.1, 0.0, 0.01;
        Eigen::Matrix3d F;
        ControlJacobian G;
        const Pose2 moved = odometry.Move(ekf.PoseOf(0), u, 0.1, &F, &G);
        ekf.PredictPose(0, moved, F, G, odometry.Noise(u, 0.1));
      }
    }
    ekf.ApplyPendingDowndate();
    for (int k = 0; k < matched; ++k) {
      const int observed[] = {kPoseKind, blocks[k * landmarks / matched]};
      const Eigen::Vector2d z = model.Predict(ekf, observed).z + rng.MultivariateNormal(R);
      sightings.push_back({&model, {observed[0], observed[1]}, 2, z, R});
    }
  }

  RangeBearingModel sensor;
  BlockEkf ekf;
  int kind;
  PointLandmarkModel model;
  std::vector<int> blocks;
  std::vector<MatchedObservation> sightings;
};

enum Policy { kAll, kCovariance, kEntropy, kEntropyFast };

std::unique_ptr<SelectionPolicy> MakePolicy(int policy) {
  switch (policy) {
    case kCovariance: return std::make_unique<SelectByCovariance>();
    case kEntropy: return std::make_unique<SelectByEntropy>();
    case kEntropyFast: return std::make_unique<SelectByEntropyFast>();
    default: return std::make_unique<SelectAll>();
  }
}

const char* PolicyName(int policy) {
  constexpr const char* kNames[] = {"all", "covariance", "entropy", "entropy-fast"};
  return kNames[policy];
}

// Seconds for one correction step of `policy` on `ekf`.
double TimeStep(BlockEkf& ekf, const std::vector<MatchedObservation>& sightings,
                SelectionPolicy& policy, SelectionStats* stats = nullptr) {
  const auto start = std::chrono::steady_clock::now();
  BlockSelectionSession session(ekf, sightings, stats != nullptr);
  policy.Select(session);
  ekf.ApplyPendingDowndate();
  benchmark::ClobberMemory();
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  if (stats != nullptr) *stats = session.stats();
  return elapsed.count();
}

// Arguments: landmarks, policy, matched sightings per step.
void BM_SelectionStep(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const int which = static_cast<int>(state.range(1));
  const int matched = static_cast<int>(state.range(2));
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  const MappedFilter mapped(landmarks, matched);
  const std::unique_ptr<SelectionPolicy> policy = MakePolicy(which);
  SelectAll all;
  SelectionStats stats;
  BlockEkf ekf = mapped.ekf;
  TimeStep(ekf, mapped.sightings, *policy, &stats);  // diagnostics once, untimed
  double policy_s = 0.0, all_s = 0.0;
  for (auto _ : state) {
    ekf = mapped.ekf;
    const double t = TimeStep(ekf, mapped.sightings, *policy);
    ekf = mapped.ekf;
    all_s += TimeStep(ekf, mapped.sightings, all);
    policy_s += t;
    state.SetIterationTime(t);
  }
  state.SetLabel(PolicyName(which));
  state.counters["N"] = landmarks;
  state.counters["matched"] = matched;
  state.counters["vs_all"] = policy_s / all_s;
  state.counters["applied"] = stats.applied;
  state.counters["accuracy"] = stats.accuracy().value_or(0.0);
}

BENCHMARK(BM_SelectionStep)
    ->ArgsProduct({{50, 100, 200}, {kAll, kCovariance, kEntropy, kEntropyFast}, {kMatched}})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
// The scaling in N (issue 10: up to 2,000) of the policies that stay O(n²) per update; the
// dense entropy policy's O(n³) per sighting would take minutes a step there.
BENCHMARK(BM_SelectionStep)
    ->Name("BM_SelectionStepLarge")
    ->ArgsProduct({{500, 1000, 2000}, {kAll, kCovariance, kEntropyFast}, {kMatched}})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);
// Flat in the sightings per step: the covariance policy's cost is bounded by k_max updates.
BENCHMARK(BM_SelectionStep)
    ->Name("BM_SelectionStepSightings")
    ->ArgsProduct({{500}, {kAll, kCovariance}, {5, 10, 20, 40}})
    ->UseManualTime()
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace slamkit
