// Throughput of occupancy-grid RBPF SLAM on the start of the Intel Research Lab log (scans per
// second for 10, 30 and 100 particles), and of the scan matcher and P-SLAM's predictor alone on a
// map built from it.

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <benchmark/benchmark.h>

#include "slamkit/filters/graph/correlative_matcher.hpp"
#include "slamkit/filters/grid/rbpf_grid_slam.hpp"
#include "slamkit/io/carmen_reader.hpp"
#include "slamkit/planning/structure_predictor.hpp"

namespace slamkit {
namespace {

constexpr int kScans = 1500;
constexpr double kUsableRangeM = 30.0;  // RbpfGridSlamParams::usable_range_m

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

// Args: particles, whether scans between updates are tracked (1) or carried by odometry (0).
void BM_GridSlamScans(benchmark::State& state) {
  const CarmenLog* log = IntelLog();
  if (!log) return state.SkipWithError("intel.clf not found");
  RbpfGridSlamParams params;
  params.particles = static_cast<int>(state.range(0));
  params.tracking_mode = state.range(1) != 0 ? TrackingMode::kTrackedMotion : TrackingMode::kOff;
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

// The map a 30-particle run built over the benchmark's scans, and its best path.
struct BuiltMap {
  OccupancyGrid map;
  Trajectory path;
};

const BuiltMap* IntelMap() {
  static const std::unique_ptr<BuiltMap> built = []() -> std::unique_ptr<BuiltMap> {
    const CarmenLog* log = IntelLog();
    if (!log) return nullptr;
    RbpfGridSlam slam(RbpfGridSlamParams{});
    for (const LaserScan& scan : log->scans) slam.ProcessScan(scan);
    return std::make_unique<BuiltMap>(BuiltMap{slam.BestMap(), slam.BestTrajectory()});
  }();
  return built.get();
}

// One MatchScan of the last scan from a pose 10 cm and 3° off (the particles' matcher, coarse
// pass included), and from 1 cm and 0.6° off (the tracking matcher).
void BM_ScanMatcher(benchmark::State& state) {
  const BuiltMap* built = IntelMap();
  if (!built) return state.SkipWithError("intel.clf not found");
  const bool tracking = state.range(0) != 0;
  const RbpfGridSlamParams defaults;
  const ScanMatcherParams& params = tracking ? defaults.tracking : defaults.matcher;
  const ScanPoints points = PrepareScan(IntelLog()->scans.back(), kUsableRangeM, params);
  const Pose2 offset = tracking ? Pose2(0.01, 0.0, 0.01) : Pose2(0.1, 0.0, 0.05);
  const Pose2 start = built->path.back().pose.Compose(offset);
  for (auto _ : state) {
    benchmark::DoNotOptimize(MatchScan(built->map, points, start, params));
  }
  state.counters["beams"] = double(points.ends.size());
}

// The reference for BM_EvaluatePose: the same score with every cell read on its own (a tile
// lookup per cell), as EvaluatePose did before it read a window's cells from one tile.
double ReferenceScore(const OccupancyGrid& grid, const ScanPoints& points, const Pose2& pose,
                      const ScanMatcherParams& params) {
  double score = 0.0;
  const double r = grid.resolution(), inv = 1.0 / (params.score_sigma_m * params.score_sigma_m);
  for (std::size_t i = 0; i < points.ends.size(); ++i) {
    const Eigen::Vector2d end = pose.rotation() * points.ends[i] + pose.translation();
    const CellIndex c = grid.WorldToCell(end);
    const CellIndex f = grid.WorldToCell(end - r * (pose.rotation() * points.directions[i]));
    double best = std::numeric_limits<double>::infinity();
    for (int dx = -params.search_cells; dx <= params.search_cells; ++dx) {
      for (int dy = -params.search_cells; dy <= params.search_cells; ++dy) {
        if (grid.LogOddsSteps({c.x + dx, c.y + dy}) <= 0) continue;
        if (grid.LogOddsSteps({f.x + dx, f.y + dy}) >= 0) continue;
        best = std::min(best, (grid.CellCenter({c.x + dx, c.y + dy}) - end).squaredNorm());
      }
    }
    if (std::isfinite(best)) score += std::exp(-best * inv);
  }
  return score;
}

// One evaluation of the score at a pose 2 cm and 1° off; first arg 1 runs the cell-by-cell
// reference (a full scan of each window), the second is the window's half-width in cells (1 as
// the fine pass, 3 as the coarse pass, where the ring-by-ring search stops early).
void BM_EvaluatePose(benchmark::State& state) {
  const BuiltMap* built = IntelMap();
  if (!built) return state.SkipWithError("intel.clf not found");
  ScanMatcherParams params;
  params.search_cells = int(state.range(1));
  const ScanPoints points = PrepareScan(IntelLog()->scans.back(), kUsableRangeM, params);
  const Pose2 pose = built->path.back().pose.Compose(Pose2(0.02, 0.0, 0.0175));
  for (auto _ : state) {
    if (state.range(0) == 0) {
      benchmark::DoNotOptimize(EvaluatePose(built->map, points, pose, params));
    } else {
      benchmark::DoNotOptimize(ReferenceScore(built->map, points, pose, params));
    }
  }
}

// One step of the hill climb at its optimum: the six moves around the match of the last scan
// scored against the match's score, as HillClimb compares them. Arg 0: 0 scores every beam
// (EvaluatePose, the reference), 1 stops once a move cannot beat the match (EvaluatePoseAbove,
// what the climb does); arg 1: the step, 0 the climb's first (5 cm, 0.05 rad), 1 its last
// (1/32 of that).
void BM_ClimbStep(benchmark::State& state) {
  const BuiltMap* built = IntelMap();
  if (!built) return state.SkipWithError("intel.clf not found");
  const ScanMatcherParams params = RbpfGridSlamParams{}.matcher;
  const ScanPoints points = PrepareScan(IntelLog()->scans.back(), kUsableRangeM, params);
  const MatchResult match = MatchScan(built->map, points, built->path.back().pose, params);
  const double scale = state.range(1) == 0 ? 1.0 : 1.0 / 32.0;
  const double lin = params.linear_step_m * scale, ang = params.angular_step_rad * scale;
  const Pose2& m = match.pose;
  const Pose2 moves[6] = {{m.x() + lin, m.y(), m.theta()}, {m.x() - lin, m.y(), m.theta()},
                          {m.x(), m.y() + lin, m.theta()}, {m.x(), m.y() - lin, m.theta()},
                          {m.x(), m.y(), m.theta() + ang}, {m.x(), m.y(), m.theta() - ang}};
  const double best = match.quality.score;
  for (auto _ : state) {
    for (const Pose2& move : moves) {
      if (state.range(0) == 0) {
        benchmark::DoNotOptimize(EvaluatePose(built->map, points, move, params));
      } else {
        benchmark::DoNotOptimize(EvaluatePoseAbove(built->map, points, move, params, best));
      }
    }
  }
  state.counters["beams"] = double(points.ends.size());
}

// P-SLAM's predictor on the map built above, as its thread runs it on a log (SPEC S4): arg 0
// chooses the target only (the nearest reachable frontier from the last pose: frontier regions
// and Dijkstra over the map), 1 predicts at that target only (lines, corners, the alignments and
// Ψ), 2 does both, as MakeStructurePredictor's call does. BM_ScanMatcher/0, one particle's match,
// is the reference in the same run.
void BM_StructurePredictor(benchmark::State& state) {
  const BuiltMap* built = IntelMap();
  if (!built) return state.SkipWithError("intel.clf not found");
  const StructurePredictorParams params;
  const Pose2 pose = built->path.back().pose;
  const std::optional<Eigen::Vector2d> target = ChoosePredictionTarget(built->map, pose, params);
  if (!target) return state.SkipWithError("no reachable frontier");
  const StructurePredictor predictor = MakeStructurePredictor(params);
  const StructurePredictionRequest request{0, 0.0, built->map, pose, std::nullopt};
  int alignments = 0;
  for (auto _ : state) {
    if (state.range(0) == 0) {
      benchmark::DoNotOptimize(ChoosePredictionTarget(built->map, pose, params));
    } else if (state.range(0) == 1) {
      const std::optional<PredictedStructure> p = PredictStructure(built->map, *target, params);
      alignments = p ? p->hypothesis.alignments : 0;
    } else {
      benchmark::DoNotOptimize(predictor(request));
    }
  }
  state.counters["alignments"] = alignments;
}

// The loop-closure search of a graph back end: the last Intel scan matched against the whole
// Intel map from 0.5 m and 0.1 rad off, over ±1 m and ±0.2 rad, exhaustively (0) and by branch
// and bound (1); the same match either way (tests/filters/graph).
void BM_CorrelativeMatcher(benchmark::State& state) {
  const BuiltMap* built = IntelMap();
  if (!built) return state.SkipWithError("intel.clf not found");
  const LaserScan& scan = IntelLog()->scans.back();
  std::vector<Eigen::Vector2d> points;  // in the robot frame
  for (int i = 0; i < static_cast<int>(scan.ranges_m.size()); ++i) {
    if (!scan.IsReturn(i) || scan.ranges_m[i] > 30.0f) continue;
    const double r = scan.ranges_m[i], a = scan.BeamAngle(i);
    points.push_back(scan.laser_offset.TransformFrom({r * std::cos(a), r * std::sin(a)}));
  }
  CorrelativeMatcherParams params;
  params.linear_window_m = 1.0;
  params.angular_window_rad = 0.2;
  params.min_score = 0.0;  // report the best whatever it scores
  static const CorrelativeMatcher matcher(built->map, params);
  const Pose2 start = built->path.back().pose.Compose(Pose2(0.4, -0.3, 0.1));
  double score = 0.0;
  for (auto _ : state) {
    const std::optional<CorrelativeMatch> m = state.range(0) == 0
                                                  ? matcher.Exhaustive(points, start)
                                                  : matcher.BranchAndBound(points, start);
    score = m ? m->score : 0.0;
  }
  state.counters["score"] = score;
  const std::optional<CorrelativeMatch> m = matcher.BranchAndBound(points, start);
  // How far the match is from the filter's own final pose, in millimetres.
  if (m) {
    state.counters["off_mm"] =
        1e3 * (m->pose.translation() - built->path.back().pose.translation()).norm();
  }
  state.counters["points"] = double(points.size());
}

BENCHMARK(BM_GridSlamScans)
    ->Args({10, 1})->Args({30, 1})->Args({100, 1})->Args({30, 0})
    ->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ScanMatcher)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_EvaluatePose)
    ->Args({0, 1})->Args({1, 1})->Args({0, 3})->Args({1, 3})->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_ClimbStep)
    ->Args({0, 0})->Args({1, 0})->Args({0, 1})->Args({1, 1})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StructurePredictor)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CorrelativeMatcher)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace slamkit
