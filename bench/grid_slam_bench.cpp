// Throughput of occupancy-grid RBPF SLAM on the start of the Intel Research Lab log (scans per
// second for 10, 30 and 100 particles), and of the scan matcher alone on a map built from it.

#include <filesystem>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "slamkit/filters/rbpf_grid_slam.hpp"
#include "slamkit/io/carmen_reader.hpp"

namespace slamkit {
namespace {

constexpr int kScans = 1500;

// Read once for all benchmarks; null when the data set is not beside the project.
const CarmenLog* IntelLog() {
  static const std::unique_ptr<CarmenLog> log = []() -> std::unique_ptr<CarmenLog> {
    const std::filesystem::path path = std::string(SLAMKIT_DATASETS_DIR) + "/carmen/intel.clf";
    if (!std::filesystem::exists(path)) return nullptr;
    auto l = std::make_unique<CarmenLog>(ReadCarmenLog(path));
    if (static_cast<int>(l->scans.size()) > kScans) l->scans.resize(kScans);
    return l;
  }();
  return log.get();
}

void BM_GridSlamScans(benchmark::State& state) {
  const CarmenLog* log = IntelLog();
  if (!log) return state.SkipWithError("intel.clf not found");
  RbpfGridSlamParams params;
  params.particles = static_cast<int>(state.range(0));
  int updates = 0;
  for (auto _ : state) {
    RbpfGridSlam slam(params);
    for (const LaserScan& scan : log->scans) slam.ProcessScan(scan);
    updates = slam.updates();
    benchmark::DoNotOptimize(slam.CurrentPose());
  }
  state.counters["scans_per_s"] = benchmark::Counter(
      double(log->scans.size()) * state.iterations(), benchmark::Counter::kIsRate);
  state.counters["updates"] = updates;
}

// One MatchScan from a pose 10 cm and 3° off, against the map a 30-particle run built.
void BM_ScanMatcher(benchmark::State& state) {
  const CarmenLog* log = IntelLog();
  if (!log) return state.SkipWithError("intel.clf not found");
  RbpfGridSlamParams params;
  RbpfGridSlam slam(params);
  for (const LaserScan& scan : log->scans) slam.ProcessScan(scan);
  const Trajectory path = slam.BestTrajectory();
  const LaserScan& scan = log->scans.back();
  const ScanPoints points = PrepareScan(scan, params.matcher);
  const Pose2 start = path.back().pose.Compose(Pose2(0.1, 0.0, 0.05));
  for (auto _ : state) {
    benchmark::DoNotOptimize(MatchScan(slam.BestMap(), points, start, params.matcher));
  }
  state.counters["beams"] = double(points.ends.size());
}

BENCHMARK(BM_GridSlamScans)->Arg(10)->Arg(30)->Arg(100)->Unit(benchmark::kMillisecond)
    ->Iterations(1);
BENCHMARK(BM_ScanMatcher)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace slamkit
