// EKF-SLAM steps with compressed updates (Guivant & Nebot 2001) against dense ones, on the same
// mapped world and the same drive: a robot circling among N landmarks spread over a square whose
// side grows with N (constant density), seeing those within 10 m. One iteration is one step
// (prediction and the step's sightings); the compressed filter's global updates fall inside the
// iterations as the robot leaves its areas, so the mean includes them. Compare the two at the
// same N in one run (`--benchmark_filter=BM_EkfLap`). N = 10,000 holds two 20,003² covariances
// (3.2 GB each) and needs a long --benchmark_min_time for the compressed run to span its areas.

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

constexpr double kDensityPerM2 = 0.1;
constexpr double kStepM = 0.2;

struct Lap {
  std::vector<Eigen::Vector2d> world;
  RangeBearingModel sensor{RangeBearingParams{.max_range_m = 10.0, .fov_rad = std::numbers::pi,
                                              .sigma_range_m = 0.05, .sigma_bearing_rad = 0.005}};
  double circle_m = 0.0;
};

// N landmarks uniform over a square of N / density m², the robot's circle at 0.35 of its side.
Lap MakeLap(int landmarks) {
  Lap lap;
  const double half = 0.5 * std::sqrt(landmarks / kDensityPerM2);
  Rng rng(32);
  for (int i = 0; i < landmarks; ++i) {
    lap.world.emplace_back(rng.Uniform(-half, half), rng.Uniform(-half, half));
  }
  lap.circle_m = 0.7 * half;
  return lap;
}

// A filter that has mapped every landmark (each added once from the true start pose, so the map
// is consistent with the sightings the drive makes).
EkfSlam MakeFilter(const Lap& lap, EkfUpdateMode update, double hysteresis) {
  EkfSlamParams params;
  params.association_method = AssociationMethod::kKnown;
  params.update = update;
  params.active_area.hysteresis_fraction = hysteresis;
  params.initial_landmark_capacity = static_cast<int>(lap.world.size());
  EkfSlam slam(params, std::make_unique<OdometryModel>(),
               std::make_unique<RangeBearingModel>(lap.sensor.params()));
  const Pose2 start(lap.circle_m, 0.0, std::numbers::pi / 2);
  slam.Reset(start, Eigen::Vector3d(1e-6, 1e-6, 1e-8).asDiagonal());
  Rng rng(33);
  for (std::size_t i = 0; i < lap.world.size(); ++i) {
    PointObservation obs;
    const Eigen::Vector2d z = RangeBearingModel().Predict(start, lap.world[i]);
    obs.z = z + Eigen::Vector2d(rng.Normal(0, 0.05), rng.Normal(0, 0.005));
    obs.R = lap.sensor.NoiseCovariance();
    obs.id = static_cast<LandmarkId>(i);
    slam.AddLandmark(obs);
  }
  return slam;
}

template <EkfUpdateMode kUpdate>
void BM_EkfLapStep(benchmark::State& state) {
  const Lap lap = MakeLap(static_cast<int>(state.range(0)));
  // Second argument: the area's hysteresis in hundredths of the sensor's range.
  EkfSlam slam = MakeFilter(lap, kUpdate, 0.01 * static_cast<double>(state.range(1)));
  Pose2 truth(lap.circle_m, 0.0, std::numbers::pi / 2);
  const Pose2 move(kStepM, 0.0, kStepM / lap.circle_m);
  Rng rng(34);
  std::vector<PointObservation> scan;
  double sightings = 0;
  for (auto _ : state) {
    truth = truth.Compose(move);
    Control u(3);
    u << move.x() + rng.Normal(0, 0.01), rng.Normal(0, 0.01), move.theta() + rng.Normal(0, 0.001);
    scan.clear();
    for (std::size_t i = 0; i < lap.world.size(); ++i) {
      if (!lap.sensor.IsVisible(truth, lap.world[i])) continue;
      PointObservation obs;
      obs.z = lap.sensor.Predict(truth, lap.world[i]) +
              Eigen::Vector2d(rng.Normal(0, 0.05), rng.Normal(0, 0.005));
      obs.R = lap.sensor.NoiseCovariance();
      obs.id = static_cast<LandmarkId>(i);
      scan.push_back(obs);
    }
    sightings += static_cast<double>(scan.size());
    slam.Predict(u, 0.1);
    benchmark::DoNotOptimize(slam.Update(scan));
  }
  state.counters["N"] = static_cast<double>(lap.world.size());
  state.counters["sightings_per_step"] = sightings / static_cast<double>(state.iterations());
  state.counters["global_updates"] = static_cast<double>(slam.Compression().global_updates);
  state.counters["max_active_size"] = slam.Compression().max_active_size;
}

BENCHMARK_TEMPLATE(BM_EkfLapStep, EkfUpdateMode::kDense)
    ->Name("BM_EkfLapStepDense")
    ->Args({500, 50})
    ->Args({2000, 50})
    ->Args({10000, 50})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_EkfLapStep, EkfUpdateMode::kCompressed)
    ->Name("BM_EkfLapStepCompressed")
    ->ArgsProduct({{500, 2000}, {10, 25, 50, 100}})
    ->ArgsProduct({{10000}, {50, 100}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slamkit
