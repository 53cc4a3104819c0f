#pragma once

#include <functional>
#include <future>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "slamkit/filters/grid/rbpf_grid_slam.hpp"
#include "slamkit/filters/grid/structure_hypothesis.hpp"
#include "slamkit/filters/grid_slam.hpp"

namespace slamkit {

// What the prediction thread gets: a copy of the best particle's map (it shares the tiles, which
// the filter then copies before writing), the particle's pose, and the target frontier point f,
// or none for the predictor to choose one.
struct StructurePredictionRequest {
  int id = 0;
  double t_s = 0.0;
  OccupancyGrid map;
  Pose2 pose;
  std::optional<Eigen::Vector2d> target_m;
};

// The look-ahead mapping (SPEC S4, steps 1-4; planning/structure_predictor.hpp makes one). It
// runs on the prediction thread and sees nothing but the request. None: nothing to predict from
// (no target, no corner); a hypothesis that is not `accepted` was scored below the threshold.
struct PredictedStructure {
  GridHypothesis hypothesis;
  bool accepted = false;
  // False when the target had no structure to align (no corner near it): only
  // hypothesis.target_m is then meaningful, so that the record says where the predictor looked.
  bool structure_found = true;
};
using StructurePredictor =
    std::function<std::optional<PredictedStructure>(const StructurePredictionRequest&)>;

struct PredictiveGridSlamParams {
  // SPEC S4 (c), seed Eq. 23: once at least one particle's scan puts min_support_beams beams on
  // a hypothesis's unexplored cells and no such particle's hit ratio reaches the threshold, the
  // hypothesis is dropped. The seed gives no hr_th; 0.5 asks that most of those beams end on a
  // predicted wall.
  bool recovery = true;
  double hit_ratio_threshold = 0.5;
  int min_support_beams = 10;
  int hit_window_cells = 1;  // a beam end this close to a predicted occupied cell is a hit
  // On a log there is no explorer to name targets: after every `request_every_updates` updates
  // with no prediction in flight, the predictor is asked to choose one itself.
  bool automatic_targets = true;
  int request_every_updates = 10;
  // 0: a result is taken at the first scan after the prediction thread finishes it, so the filter
  // never waits, and which scan that is depends on the machine's load. k > 0: exactly k scans
  // after the request, waiting for the thread then if need be: the same seed gives the same run,
  // bit for bit.
  int deterministic_delay_scans = 0;
  // V (seed Section IV): a hypothesis with fewer unexplored cells left than this share of its
  // own is explored, and retired.
  double retire_below_unexplored_fraction = 0.1;
};

enum class HypothesisFate {
  kInFlight,           // the prediction thread is still on it
  kNoStructure,        // no target, or no corner to align
  kBelowThreshold,     // the best alignment's Ψ was below the threshold
  kActive,             // in the particles' second layers (at the end: never explored)
  kExplored,           // retired by validation
  kDroppedByRecovery,  // no particle's scan supported it
};
const char* HypothesisFateName(HypothesisFate fate);

// One prediction request and what became of it (hypotheses.csv).
struct HypothesisRecord {
  int request_scan = 0;
  int install_scan = -1;  // when its result was taken
  int end_scan = -1;      // when it was retired or dropped
  HypothesisFate fate = HypothesisFate::kInFlight;
  GridHypothesis hypothesis;  // its cells, in the frame of the map it was predicted from
  double best_hit_ratio = -1.0;  // the largest hr measured on enough beams; −1: never measured
  int unexplored_cells = 0;      // at the end (or when it left the layers)
};

// P-SLAM (SPEC S4): the grid RBPF with predicted structure. Each accepted hypothesis goes into
// every particle's second map layer, moved by that particle's pose relative to the best one's
// (the seed adjusts one prediction to each particle instead of predicting per particle). The
// proposal and the weight read a particle's map through that view, so beams ending on cells the
// map has not explored are scored against h by the same sensor model: the weight is
// S1(z_e | m) · S2(z_u | h) of seed Eqs. 21-22 in one term (adding S2 again as a factor would
// count z_u twice), and it applies only until the map explores those cells, as the seed says.
// The filter's extra weight factor measures each hypothesis's support (Eq. 23) for recovery.
class PredictiveGridSlam final : public GridSlam {
 public:
  PredictiveGridSlam(const RbpfGridSlamParams& rbpf, const PredictiveGridSlamParams& params,
                     StructurePredictor predictor);
  ~PredictiveGridSlam() override;

  bool ProcessScan(const LaserScan& scan) override;
  Pose2 CurrentPose() override { return rbpf_.CurrentPose(); }
  Trajectory BestTrajectory() override { return rbpf_.BestTrajectory(); }
  const OccupancyGrid& BestMap() const override { return rbpf_.BestMap(); }
  GridSlamStats Stats() const override { return rbpf_.Stats(); }
  void CheckOutputHealth() const override { rbpf_.CheckOutputHealth(); }

  // Asks for a prediction at the target point f (the explorer's next goal). While one is in
  // flight, the latest request waits for it.
  void RequestPrediction(const Eigen::Vector2d& target_m);
  // Waits for the prediction in flight and takes it (before output).
  void Flush();
  // The predicted cells the best particle sees where its map is unknown (null: none).
  const OccupancyGrid* BestPredictedLayer() const;
  const std::vector<HypothesisRecord>& records() const { return records_; }
  const RbpfGridSlam& rbpf() const { return rbpf_; }

 private:
  struct Active {
    int record;
    std::vector<Pose2> to_particle;  // the hypothesis's frame to each particle's
    std::vector<HypothesisSupport> support;  // at the current update, per particle
  };
  double MeasureAll(const GridWeightContext& context);
  void Submit(std::optional<Eigen::Vector2d> target_m, double t_s);
  void TakeFinished(bool wait);
  void Install(int record);
  void AfterUpdate();
  bool DropUnsupported(Active& active);
  void Retire(std::size_t index, HypothesisFate fate);
  void RebuildLayers();

  PredictiveGridSlamParams params_;
  StructurePredictor predictor_;
  RbpfGridSlam rbpf_;
  std::vector<HypothesisRecord> records_;
  std::vector<Active> active_;
  std::future<std::optional<PredictedStructure>> in_flight_;
  int in_flight_record_ = -1;
  std::optional<Eigen::Vector2d> queued_target_;
  int scans_ = 0;
  double last_t_s_ = 0.0;
  int updates_since_request_ = 0;
};

}  // namespace slamkit
