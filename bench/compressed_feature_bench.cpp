// The line-and-corner EKF-SLAM of SPEC S1 with compressed updates (Guivant & Nebot 2001)
// against dense ones, on the same simulated run: the serpentine route through every corridor of
// a square maze of k × k blocks (MakeSquareMaze, 3.5 m blocks, 2.2 m corridors), a 10 m laser,
// the features extracted once beforehand. One iteration is the whole run (prediction and update
// per scan); `step_us` is its mean per scan, the compressed run's global updates included.
// Second argument: the selection policy, 0 the covariance policy with k_max 3 (SPEC S1 item 3,
// the logs' default), 1 every matched sighting applied; third: the distance between scans in cm
// (the robot's speed at 10 Hz), so the number of scans an area lasts. Compare the two modes at the same
// arguments in one run (`--benchmark_filter=BM_FeatureMaze`).

#include <benchmark/benchmark.h>

#include <chrono>
#include <map>
#include <utility>
#include <memory>
#include <vector>

#include "slamkit/features/scan_features.hpp"
#include "slamkit/filters/features/feature_ekf_slam.hpp"
#include "slamkit/filters/selection/selection_policies.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/sim/laser_sim.hpp"
#include "slamkit/sim/maze_route.hpp"

namespace slamkit {
namespace {

struct MazeFeatures {
  Pose2 start;
  std::vector<Pose2> moves;  // odometry between consecutive scans
  std::vector<ScanFeatures> scans;
};

const MazeFeatures& Features(int blocks, int spacing_cm) {
  static std::map<std::pair<int, int>, MazeFeatures> cache;
  auto [it, fresh] = cache.try_emplace({blocks, spacing_cm});
  if (!fresh) return it->second;
  SquareMazeParams maze;
  maze.outer_size_m = 2 * 2.2 + blocks * 3.5 + (blocks - 1) * 2.2;
  const FloorPlan plan = MakeSquareMaze(maze);
  GridSimParams params;
  params.route = MazeRoute(maze);
  params.speed_mps = 0.1 * spacing_cm;  // scans at 10 Hz
  params.laser.beams = 181;
  params.laser.range_limit_m = 10.0;
  params.laser.sigma_range_m = 0.01;
  Rng rng(2032);
  const GridSimRun sim = SimulateGridRun(plan, params, RouteStartPose(params.route), rng);
  LineExtractionParams extraction;
  extraction.max_usable_range_m = 10.0;
  extraction.sigma_range_m = 0.01;
  MazeFeatures& f = it->second;
  f.start = sim.truth[0].pose;
  for (std::size_t k = 0; k < sim.scans.size(); ++k) {
    const LaserScan& scan = sim.scans[k];
    if (k > 0) f.moves.push_back(sim.scans[k - 1].odometry.Between(scan.odometry));
    f.scans.push_back(ToRobotFrame(ExtractFeatures(scan, extraction), scan.laser_offset));
  }
  return f;
}

template <EkfUpdateMode kUpdate>
void BM_FeatureMaze(benchmark::State& state) {
  const MazeFeatures& f =
      Features(static_cast<int>(state.range(0)), static_cast<int>(state.range(2)));
  OdometryParams odometry;
  odometry.sigma_xy_m = 0.015;
  odometry.sigma_theta_rad = 0.006;
  FeatureEkfSlamParams params;
  params.update = kUpdate;
  params.area_reach_m = 10.0;
  params.corner_reach_m = 10.0;
  CovarianceSelectionParams selection;
  selection.k_max = 3;
  long global_updates = 0;
  int state_size = 0;
  double seconds = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<SelectionPolicy> policy;
    if (state.range(1) == 0) policy = std::make_unique<SelectByCovariance>(selection);
    FeatureEkfSlam slam(params, std::make_unique<OdometryModel>(odometry), std::move(policy));
    slam.Reset(f.start);
    for (std::size_t k = 0; k < f.scans.size(); ++k) {
      if (k > 0) slam.Predict(f.moves[k - 1].vector(), 0.1);
      slam.Update(f.scans[k]);
    }
    slam.Synchronise();
    benchmark::DoNotOptimize(slam.pose());
    global_updates = slam.Compression().global_updates;
    state_size = slam.ekf().StateSize();
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  state.counters["scans"] = static_cast<double>(f.scans.size());
  state.counters["state"] = state_size;
  state.counters["global_updates"] = static_cast<double>(global_updates);
  state.counters["step_us"] = 1e6 * seconds / static_cast<double>(f.scans.size());
}

BENCHMARK_TEMPLATE(BM_FeatureMaze, EkfUpdateMode::kDense)
    ->ArgsProduct({{5, 10}, {0, 1}, {20, 5}})->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK_TEMPLATE(BM_FeatureMaze, EkfUpdateMode::kCompressed)
    ->ArgsProduct({{5, 10}, {0, 1}, {20, 5}})->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace slamkit
