// FastSLAM step time against the size of the map (issue 11): 100 particles, a map of N landmarks
// built directly, then per step a prediction, a scan of 5 sightings of existing landmarks (known
// association) and a resampling (forced: threshold above 1). Times are CPU times of the step.
//
// BM_FastSlamStep runs FastSlam, whose particles share their landmarks in a persistent tree
// (LandmarkTree): resampling copies a particle in O(1) and an update copies O(log N) nodes, so
// the step should grow like log N. BM_FlatMapStep is the naive baseline: the same per-particle
// arithmetic with a flat std::vector map per particle, copied whole by resampling: O(N) per
// particle per step. Both report bytes_per_particle: the memory the set holds divided by the
// particles (for the tree, every distinct node once, however many particles share it).

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <benchmark/benchmark.h>

#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf/kalman_update.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/filters/particles/particle_set.hpp"
#include "slamkit/filters/particles/particle_streams.hpp"
#include "slamkit/models/motion_sampling.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

constexpr int kParticles = 100;
constexpr int kSightings = 5;
constexpr std::uint64_t kFastSlamBenchSeed = 20240611;

// N landmarks on a square grid of 2 m spacing, offset from the origin where the robot stays.
LandmarkMap GridMap(int n) {
  const int side = static_cast<int>(std::ceil(std::sqrt(double(n))));
  LandmarkMap map;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d p(1.0 + 2.0 * (i % side), 1.0 + 2.0 * (i / side));
    map.landmarks.push_back({i, p, 0.01 * Eigen::Matrix2d::Identity()});
  }
  return map;
}

Control Still() { return Control::Zero(3); }

// A scan of kSightings landmarks with consecutive indexes from a random start, seen without
// noise from the origin: what a robot sees together was mapped together, so a scan's landmarks
// are neighbours in the tree, while the scans of successive steps land anywhere in the map.
std::vector<PointObservation> Scan(const LandmarkMap& map, const RangeBearingModel& sensor,
                                   Rng& rng) {
  const int n = static_cast<int>(map.landmarks.size());
  const int first = static_cast<int>(rng.Uniform(0.0, double(n - kSightings) - 1e-6));
  std::vector<PointObservation> scan(kSightings);
  for (int k = 0; k < kSightings; ++k) {
    scan[k].z = sensor.Predict(Pose2(), map.landmarks[first + k].position_m);
    scan[k].R = sensor.NoiseCovariance();
    scan[k].id = first + k;
  }
  return scan;
}

std::size_t TreeBytesPerParticle(const FastSlam& slam) {
  std::vector<const LandmarkTree<FastSlamLandmark>*> trees;
  for (int k = 0; k < slam.particles().size(); ++k) trees.push_back(&slam.particles()[k].landmarks);
  return LandmarkTree<FastSlamLandmark>::CountDistinctNodes(trees).bytes() / trees.size();
}

void BM_FastSlamStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const LandmarkMap map = GridMap(n);
  const RangeBearingModel sensor;
  FastSlamParams params;
  params.particles = kParticles;
  params.proposal = FastSlamProposal::kMotion;
  params.known_association = true;
  params.resampling.threshold = 2.0;  // resample at every step
  FastSlam slam(params, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>());
  slam.Reset(Pose2());
  slam.AddLandmarks(map);
  Rng rng(kFastSlamBenchSeed);
  for (auto _ : state) {
    state.PauseTiming();
    const std::vector<PointObservation> scan = Scan(map, sensor, rng);
    state.ResumeTiming();
    slam.Predict(Still(), 0.1);
    benchmark::DoNotOptimize(slam.Update(scan));
  }
  state.counters["N"] = n;
  state.counters["bytes_per_particle"] = double(TreeBytesPerParticle(slam));
}

// The naive baseline: one flat landmark vector per particle, copied whole by resampling.
struct FlatParticle {
  Pose2 pose;
  std::vector<FastSlamLandmark> landmarks;
};

// FastSLAM 1.0's step for FlatParticle: motion sample, landmark EKF updates, weight.
double FlatParticleStep(FlatParticle& p, const std::vector<PointObservation>& scan,
                        const OdometryModel& motion, const RangeBearingModel& sensor, Rng& rng) {
  p.pose = SampleMotion(motion, p.pose, Still(), 0.1, rng);
  double log_weight = 0.0;
  for (const PointObservation& obs : scan) {
    FastSlamLandmark& l = p.landmarks[static_cast<std::size_t>(obs.id)];
    Eigen::Matrix2d H;
    const Eigen::Vector2d nu = sensor.Innovation(obs.z, sensor.Predict(p.pose, l.mean, nullptr, &H));
    const KalmanCorrection<2, 2> k = KalmanUpdate<2, 2>(l.mean, l.covariance, nu, H, obs.R);
    l.mean = k.mean;
    l.covariance = k.covariance;
    log_weight += -0.5 * nu.dot(k.S.ldlt().solve(nu));
  }
  return log_weight;
}

void BM_FlatMapStep(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const LandmarkMap map = GridMap(n);
  const RangeBearingModel sensor;
  const OdometryModel motion;
  FlatParticle first;
  for (const MappedLandmark& m : map.landmarks) first.landmarks.push_back({m.position_m, m.covariance, 1});
  ParticleSet<FlatParticle> particles(kParticles, first);
  ParticleStreams streams(kFastSlamBenchSeed, kParticles);
  const ResamplingParams always{2.0, ResamplingScheme::kSystematic};
  Rng rng(kFastSlamBenchSeed);
  int step = 0;
  for (auto _ : state) {
    state.PauseTiming();
    const std::vector<PointObservation> scan = Scan(map, sensor, rng);
    state.ResumeTiming();
    for (int k = 0; k < kParticles; ++k) {
      Rng particle_rng = streams.ForParticle(step, k);
      particles.AddLogWeight(k, FlatParticleStep(particles[k], scan, motion, sensor, particle_rng));
    }
    ++step;
    benchmark::DoNotOptimize(particles.ResampleIfNeeded(1.0, always, streams.filter()));
  }
  state.counters["N"] = n;
  state.counters["bytes_per_particle"] =
      double(sizeof(FlatParticle) + first.landmarks.size() * sizeof(FastSlamLandmark));
}

BENCHMARK(BM_FastSlamStep)->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_FlatMapStep)->RangeMultiplier(10)->Range(100, 100000)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace slamkit
