#include "slamkit/filters/grid/predictive_grid_slam.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <future>

#include "slamkit/sim/laser_sim.hpp"

namespace slamkit {
namespace {

// A corridor 4 m wide and 30 m long, closed at both ends; the robot drives 18 m down its middle
// with a laser that sees 6 m, so the corridor's far part is unknown until the robot comes near.
FloorPlan Corridor() {
  return FloorPlan{{WallSegment{{-2.0, -2.0}, {28.0, -2.0}}, WallSegment{{-2.0, 2.0}, {28.0, 2.0}},
                    WallSegment{{-2.0, -2.0}, {-2.0, 2.0}}, WallSegment{{28.0, -2.0}, {28.0, 2.0}}}};
}

std::vector<LaserScan> DriveDownTheCorridor() {
  const FloorPlan plan = Corridor();
  Rng rng(5);
  LaserSimParams laser;
  laser.range_limit_m = 6.0;
  laser.max_range_m = 8.0;
  std::vector<LaserScan> scans;
  Pose2 pose, odometry;
  for (int k = 0; k <= 180; ++k) {
    if (k > 0) {
      pose = pose.Compose(Pose2(0.1, 0.0, 0.0));
      odometry = odometry.Compose(Pose2(0.1 + rng.Normal(0.0, 0.002), 0.0, rng.Normal(0.0, 0.002)));
    }
    LaserScan scan = SimulateScan(plan, pose, laser, rng);
    scan.t_s = 0.1 * k;
    scan.odometry = odometry;
    scans.push_back(std::move(scan));
  }
  return scans;
}

RbpfGridSlamParams SmallFilter() {
  RbpfGridSlamParams params;
  params.particles = 8;
  params.seed = 3;
  return params;
}

// A hypothesis over the corridor's cells for x in [8, 20] m (|y| up to its walls' outer cells):
// free cells with walls at y = ±wall_y_m.
StructurePredictor PredictWallsAt(double wall_y_m, std::atomic<int>* calls) {
  return [wall_y_m, calls](const StructurePredictionRequest& request)
             -> std::optional<PredictedStructure> {
    ++*calls;
    PredictedStructure result{GridHypothesis{.t_s = request.t_s,
                                             .target_m = {8.0, 0.0},
                                             .similarity = 0.9,
                                             .cells = OccupancyGrid(request.map.params())},
                              true};
    GridHypothesis& h = result.hypothesis;
    const double res = h.cells.resolution();
    const CellIndex lo = h.cells.WorldToCell({8.0, -2.04}), hi = h.cells.WorldToCell({20.0, 2.04});
    for (int cy = lo.y; cy <= hi.y; ++cy) {
      for (int cx = lo.x; cx <= hi.x; ++cx) {
        const CellIndex c{cx, cy};
        if (request.map.IsKnown(c)) continue;
        const double y = h.cells.CellCenter(c).y();
        const bool wall = std::abs(std::abs(y) - wall_y_m) <= 0.5 * res + 1e-9;
        h.cells.UpdateSteps(c, wall ? 100 : -60);
        ++h.predicted_cells;
        h.occupied_cells += wall;
      }
    }
    return result;
  };
}

std::vector<Pose2> Path(GridSlam& slam) {
  std::vector<Pose2> path;
  for (const StampedPose& p : slam.BestTrajectory()) path.push_back(p.pose);
  return path;
}

// With nothing predicted, P-SLAM is the grid RBPF, bit for bit (SPEC S4: prediction off gives
// today's results).
TEST(PredictiveGridSlam, WithoutPredictionsIsTheGridFilterBitForBit) {
  const std::vector<LaserScan> scans = DriveDownTheCorridor();
  RbpfGridSlam plain(SmallFilter());
  std::atomic<int> calls = 0;
  PredictiveGridSlamParams params;
  params.request_every_updates = 2;
  params.deterministic_delay_scans = 3;
  PredictiveGridSlam predictive(SmallFilter(), params,
                                [&calls](const StructurePredictionRequest& request) {
                                  // Every other one found no structure at a target it names.
                                  std::optional<PredictedStructure> none;
                                  if (++calls % 2 == 0) {
                                    none.emplace();
                                    none->structure_found = false;
                                    none->hypothesis.target_m = {request.id, 1.0};
                                  }
                                  return none;
                                });
  for (const LaserScan& scan : scans) {
    plain.ProcessScan(scan);
    predictive.ProcessScan(scan);
  }
  predictive.Flush();
  const std::vector<Pose2> a = Path(plain), b = Path(predictive);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_EQ(a[i].vector(), b[i].vector()) << i;
  EXPECT_GT(calls.load(), 3);  // the automatic requests ran
  ASSERT_FALSE(predictive.records().empty());
  const int last_scan = static_cast<int>(scans.size());
  for (const HypothesisRecord& r : predictive.records()) {
    EXPECT_EQ(r.fate, HypothesisFate::kNoStructure);
    if (r.hypothesis.id % 2 == 1) {
      EXPECT_EQ(r.hypothesis.target_m.x(), r.hypothesis.id);
    }
    // The deterministic schedule: 3 scans after the request, or at the Flush after the last scan.
    EXPECT_EQ(r.install_scan, std::min(r.request_scan + 3, last_scan)) << r.request_scan;
  }
}

// SPEC S4: the prediction runs on its own thread and the filter never waits for it. The
// predictor here blocks until the test releases it, after every scan has been processed: a
// filter that waited would never get there (the test would hang and time out).
TEST(PredictiveGridSlam, ASlowPredictorNeverBlocksAnUpdate) {
  const std::vector<LaserScan> scans = DriveDownTheCorridor();
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<int> calls = 0;
  PredictiveGridSlamParams params;
  params.automatic_targets = false;
  PredictiveGridSlam slam(SmallFilter(), params,
                          [released, &calls](const StructurePredictionRequest&) {
                            ++calls;
                            released.wait();
                            return std::optional<PredictedStructure>();
                          });
  slam.ProcessScan(scans.front());
  slam.RequestPrediction({8.0, 0.0});
  slam.RequestPrediction({9.0, 0.0});  // queued behind the one in flight
  int updates = 0;
  for (std::size_t k = 1; k < scans.size(); ++k) updates += slam.ProcessScan(scans[k]);
  EXPECT_GT(updates, 10);
  ASSERT_EQ(slam.records().size(), 1u);
  EXPECT_EQ(slam.records()[0].fate, HypothesisFate::kInFlight);
  release.set_value();
  slam.Flush();  // takes the first, which submits the queued one; the second Flush takes it
  slam.Flush();
  EXPECT_EQ(calls.load(), 2);
  ASSERT_EQ(slam.records().size(), 2u);
  for (const HypothesisRecord& r : slam.records()) EXPECT_EQ(r.fate, HypothesisFate::kNoStructure);
}

struct Outcome {
  HypothesisRecord record;
  bool layer_seen = false;  // the best particle had the hypothesis in its second layer
};

Outcome RunWithOneHypothesis(double wall_y_m, bool recovery) {
  const std::vector<LaserScan> scans = DriveDownTheCorridor();
  std::atomic<int> calls = 0;
  PredictiveGridSlamParams params;
  params.automatic_targets = false;
  params.deterministic_delay_scans = 1;
  params.recovery = recovery;
  PredictiveGridSlam slam(SmallFilter(), params, PredictWallsAt(wall_y_m, &calls));
  Outcome outcome;
  for (std::size_t k = 0; k < scans.size(); ++k) {
    slam.ProcessScan(scans[k]);
    if (k == 0) slam.RequestPrediction({8.0, 0.0});
    const OccupancyGrid* layer = slam.BestPredictedLayer();
    if (layer != nullptr && layer->IsKnown(layer->WorldToCell({15.0, wall_y_m}))) {
      outcome.layer_seen = true;
    }
  }
  slam.Flush();
  EXPECT_EQ(calls.load(), 1);
  outcome.record = slam.records().at(0);
  return outcome;
}

// SPEC S4 (c): the scans support the true walls (hit ratio high), so the hypothesis stays until
// the map has explored it (validation V), and is never dropped.
TEST(PredictiveGridSlam, ARightPredictionIsKeptUntilExplored) {
  const Outcome o = RunWithOneHypothesis(2.0, true);
  EXPECT_TRUE(o.layer_seen);
  EXPECT_EQ(o.record.fate, HypothesisFate::kExplored) << HypothesisFateName(o.record.fate);
  EXPECT_GE(o.record.best_hit_ratio, 0.5);
  EXPECT_LT(o.record.unexplored_cells, 0.1 * o.record.hypothesis.predicted_cells);
}

// Walls predicted 1 m inside the real ones: the beams that reach the predicted cells end on
// cells h says are free, the hit ratio stays low, and recovery drops it (Eq. 23). Without
// recovery, it stays in the layers until explored.
TEST(PredictiveGridSlam, RecoveryDropsAPredictionTheScansDoNotSupport) {
  const Outcome dropped = RunWithOneHypothesis(1.0, true);
  EXPECT_TRUE(dropped.layer_seen);
  EXPECT_EQ(dropped.record.fate, HypothesisFate::kDroppedByRecovery)
      << HypothesisFateName(dropped.record.fate);
  EXPECT_GE(dropped.record.best_hit_ratio, 0.0);  // measured
  EXPECT_LT(dropped.record.best_hit_ratio, 0.5);
  const Outcome kept = RunWithOneHypothesis(1.0, false);
  EXPECT_NE(kept.record.fate, HypothesisFate::kDroppedByRecovery);
  EXPECT_TRUE(kept.record.end_scan < 0 || kept.record.end_scan > dropped.record.end_scan);
}

}  // namespace
}  // namespace slamkit
