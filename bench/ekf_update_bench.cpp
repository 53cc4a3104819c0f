// Cost of one sequential EKF-SLAM landmark update against the kernel that bounds it.
//
// EkfSlam keeps only the upper triangle of the n×n covariance (n = 3 + 2N) and each update is a
// symmetric rank-2 downdate of that triangle plus O(n) work, so its time should approach that
// of the bare triangular rank-2 product as N grows. All three benchmarks report the bytes of one
// read and one write of the triangle, n(n+1)/2 · 8 · 2, as bytes_per_second.

#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

constexpr std::uint64_t kEkfBenchSeed = 20240611;

int StateSize(int landmarks) { return 3 + 2 * landmarks; }

void SetCounters(benchmark::State& state, int landmarks) {
  const double n = StateSize(landmarks);
  const double triangle_bytes = n * (n + 1.0) / 2.0 * sizeof(double) * 2.0;
  state.SetItemsProcessed(state.iterations());
  state.SetBytesProcessed(
      static_cast<std::int64_t>(static_cast<double>(state.iterations()) * triangle_bytes));
  state.counters["N"] = landmarks;
  state.counters["n"] = n;
}

// A sighting of `l` from `pose` with range/bearing noise drawn from the sensor's covariance.
PointObservation NoisySighting(const RangeBearingModel& sensor, const Pose2& pose,
                               const Eigen::Vector2d& l, LandmarkId id, Rng& rng) {
  const Eigen::Matrix2d R = sensor.NoiseCovariance();
  PointObservation obs;
  obs.z = sensor.Predict(pose, l) + rng.MultivariateNormal(R);
  obs.R = R;
  obs.id = id;
  return obs;
}

// A filter at the origin holding `landmarks` landmarks 1–30 m away in every direction, and for
// each one a second, independent sighting to update it with (consistent with the map, so the
// state stays sane however often the loop cycles through them).
std::unique_ptr<EkfSlam> MakeMappedFilter(int landmarks, std::vector<PointObservation>* sightings) {
  const RangeBearingModel sensor;
  EkfSlamParams params;
  params.association_method = AssociationMethod::kKnown;  // BM_EkfStep* pass sightings through Update()
  params.initial_landmark_capacity = landmarks;  // covariance stride = n, as in the references
  auto slam = std::make_unique<EkfSlam>(params, std::make_unique<OdometryModel>(),
                                        std::make_unique<RangeBearingModel>(sensor));
  const Pose2 origin;
  slam->Reset(origin, Eigen::Vector3d(1e-4, 1e-4, 1e-6).asDiagonal());
  Rng rng(kEkfBenchSeed);
  sightings->clear();
  for (int i = 0; i < landmarks; ++i) {
    const double range = rng.Uniform(1.0, 30.0);
    const double bearing = rng.Uniform(-std::numbers::pi, std::numbers::pi);
    const Eigen::Vector2d l = range * Eigen::Vector2d(std::cos(bearing), std::sin(bearing));
    slam->AddLandmark(NoisySighting(sensor, origin, l, i, rng));
    sightings->push_back(NoisySighting(sensor, origin, l, i, rng));
  }
  return slam;
}

// Second argument: worker threads for the covariance downdate (the references use one).
void BM_EkfSequentialUpdate(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(1)));
  std::vector<PointObservation> sightings;
  const std::unique_ptr<EkfSlam> slam = MakeMappedFilter(landmarks, &sightings);
  int next = 0;
  for (auto _ : state) {
    slam->UpdateLandmark(next, sightings[next]);
    slam->ApplyPendingDowndate();
    benchmark::ClobberMemory();
    next = next + 1 == landmarks ? 0 : next + 1;
  }
  if (!slam->State().allFinite() || !slam->PoseCovariance().allFinite()) {
    state.SkipWithError("EKF state became non-finite");
  }
  SetCounters(state, landmarks);
}

// One filter step of `kStepSightings` sightings: through Update(), which defers the downdates and
// applies them in one pass, or as that many single UpdateLandmark calls (one pass each). One
// thread, so the ratio shows the memory-traffic saving alone.
constexpr int kStepSightings = 25;

template <bool kDeferred>
void BM_EkfStep(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  std::vector<PointObservation> sightings;
  const std::unique_ptr<EkfSlam> slam = MakeMappedFilter(landmarks, &sightings);
  int first = 0;
  for (auto _ : state) {
    const std::span<const PointObservation> step(sightings.data() + first, kStepSightings);
    if constexpr (kDeferred) {
      benchmark::DoNotOptimize(slam->Update(step));
    } else {
      for (const PointObservation& obs : step) {
        slam->UpdateLandmark(static_cast<int>(obs.id), obs);
        slam->ApplyPendingDowndate();
      }
    }
    benchmark::ClobberMemory();
    first = first + 2 * kStepSightings > landmarks ? 0 : first + kStepSightings;
  }
  if (!slam->State().allFinite()) state.SkipWithError("EKF state became non-finite");
  state.SetItemsProcessed(state.iterations() * kStepSightings);
  state.counters["N"] = landmarks;
}

struct Rank2Operands {
  Eigen::MatrixXd P;
  Eigen::MatrixXd A;
  Eigen::MatrixXd B;
};

// Small entries so that millions of repetitions leave P far from overflow.
Rank2Operands MakeOperands(int landmarks) {
  const int n = StateSize(landmarks);
  Rng rng(kEkfBenchSeed);
  Rank2Operands ops{Eigen::MatrixXd(n, n), Eigen::MatrixXd(n, 2), Eigen::MatrixXd(n, 2)};
  for (Eigen::MatrixXd* m : {&ops.P, &ops.A, &ops.B}) {
    for (Eigen::Index i = 0; i < m->size(); ++i) m->data()[i] = rng.Uniform(-1e-3, 1e-3);
  }
  return ops;
}

// Whether `P.triangularView<Upper>() -= A Bᵀ` leaves the strictly lower triangle alone, i.e.
// compiles to Eigen's triangular product rather than a full product followed by a masked copy
// that would touch (read) every entry.
bool TriangularKernelTouchesOnlyUpper(int n) {
  Rank2Operands ops = MakeOperands((n - 3) / 2);
  const Eigen::MatrixXd before = ops.P;
  ops.P.triangularView<Eigen::Upper>() -= ops.A * ops.B.transpose();
  const Eigen::MatrixXd expected_upper = before - ops.A * ops.B.transpose();
  return ops.P.triangularView<Eigen::StrictlyLower>().toDenseMatrix() ==
             before.triangularView<Eigen::StrictlyLower>().toDenseMatrix() &&
         ops.P.triangularView<Eigen::Upper>().toDenseMatrix().isApprox(
             expected_upper.triangularView<Eigen::Upper>().toDenseMatrix());
}

void BM_ReferenceRank2Triangle(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  if (!TriangularKernelTouchesOnlyUpper(StateSize(std::min(landmarks, 100)))) {
    state.SkipWithError("triangular product wrote outside the upper triangle");
    return;
  }
  Rank2Operands ops = MakeOperands(landmarks);
  for (auto _ : state) {
    ops.P.triangularView<Eigen::Upper>() -= ops.A * ops.B.transpose();
    benchmark::DoNotOptimize(ops.P.data());
    benchmark::ClobberMemory();
  }
  SetCounters(state, landmarks);
}

void BM_ReferenceRank2Full(benchmark::State& state) {
  const int landmarks = static_cast<int>(state.range(0));
  Rank2Operands ops = MakeOperands(landmarks);
  for (auto _ : state) {
    ops.P.noalias() -= ops.A * ops.B.transpose();
    benchmark::DoNotOptimize(ops.P.data());
    benchmark::ClobberMemory();
  }
  SetCounters(state, landmarks);
}

void LandmarkCounts(benchmark::internal::Benchmark* b) {
  for (const int landmarks : {50, 100, 200, 500, 1000, 2000}) b->Arg(landmarks);
  b->Unit(benchmark::kMicrosecond);
}

void LandmarkCountsAndThreads(benchmark::internal::Benchmark* b) {
  b->ArgsProduct({{50, 100, 200, 500, 1000, 2000}, {1, 2}});
  b->Unit(benchmark::kMicrosecond);
}

void StepLandmarkCounts(benchmark::internal::Benchmark* b) {
  for (const int landmarks : {100, 500, 1000, 2000}) b->Arg(landmarks);
  b->Unit(benchmark::kMicrosecond);
}

BENCHMARK(BM_EkfSequentialUpdate)->Apply(LandmarkCountsAndThreads);
BENCHMARK_TEMPLATE(BM_EkfStep, true)->Name("BM_EkfStepDeferred")->Apply(StepLandmarkCounts);
BENCHMARK_TEMPLATE(BM_EkfStep, false)->Name("BM_EkfStepOneByOne")->Apply(StepLandmarkCounts);
BENCHMARK(BM_ReferenceRank2Triangle)->Apply(LandmarkCounts);
BENCHMARK(BM_ReferenceRank2Full)->Apply(LandmarkCounts);

}  // namespace
}  // namespace slamkit

BENCHMARK_MAIN();
