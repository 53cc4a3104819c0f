#include "slamkit/filters/grid/predictive_grid_slam.hpp"

#include <chrono>
#include <memory>
#include <stdexcept>
#include <utility>

namespace slamkit {

const char* HypothesisFateName(HypothesisFate fate) {
  switch (fate) {
    case HypothesisFate::kInFlight: return "in_flight";
    case HypothesisFate::kNoStructure: return "no_structure";
    case HypothesisFate::kBelowThreshold: return "below_threshold";
    case HypothesisFate::kActive: return "active";
    case HypothesisFate::kExplored: return "explored";
    case HypothesisFate::kDroppedByRecovery: return "dropped_by_recovery";
  }
  return "?";
}

PredictiveGridSlam::PredictiveGridSlam(const RbpfGridSlamParams& rbpf,
                                       const PredictiveGridSlamParams& params,
                                       StructurePredictor predictor)
    : params_(params),
      predictor_(std::move(predictor)),
      rbpf_(rbpf, [this](const GridWeightContext& context) { return MeasureAll(context); }) {
  if (!predictor_) throw std::invalid_argument("PredictiveGridSlam: no predictor");
  if (params_.deterministic_delay_scans < 0 || params_.request_every_updates < 1 ||
      params_.min_support_beams < 1 || params_.hit_window_cells < 0) {
    throw std::invalid_argument(
        "PredictiveGridSlam: deterministic_delay_scans must be >= 0, request_every_updates and "
        "min_support_beams >= 1, hit_window_cells >= 0");
  }
}

PredictiveGridSlam::~PredictiveGridSlam() {
  if (in_flight_.valid()) in_flight_.wait();
}

// Called for every particle at an update, from several threads: each writes its own slot.
double PredictiveGridSlam::MeasureAll(const GridWeightContext& context) {
  for (Active& active : active_) {
    const GridHypothesis& h = records_[active.record].hypothesis;
    active.support[context.particle] =
        MeasureSupport(h.cells, active.to_particle[context.particle], context.map.map,
                       context.points, context.pose, params_.hit_window_cells);
  }
  return 0.0;  // S2 is already in the view's likelihood (see the class comment)
}

bool PredictiveGridSlam::ProcessScan(const LaserScan& scan) {
  ++scans_;
  last_t_s_ = scan.t_s;
  TakeFinished(false);
  for (Active& active : active_) active.support.assign(rbpf_.particle_count(), {});
  const bool updated = rbpf_.ProcessScan(scan);
  if (updated) AfterUpdate();
  return updated;
}

void PredictiveGridSlam::RequestPrediction(const Eigen::Vector2d& target_m) {
  if (in_flight_.valid()) {
    queued_target_ = target_m;
    return;
  }
  Submit(target_m, last_t_s_);
}

void PredictiveGridSlam::Flush() { TakeFinished(true); }

// SPEC S4: prediction runs in its own thread. The map is copied here, on the filter's thread.
void PredictiveGridSlam::Submit(std::optional<Eigen::Vector2d> target_m, double t_s) {
  if (rbpf_.particle_count() == 0 || scans_ == 0) return;
  const GridParticle& best = rbpf_.particle(rbpf_.BestParticle());
  StructurePredictionRequest request{static_cast<int>(records_.size()), t_s, best.map,
                                     best.pose, target_m};
  HypothesisRecord record;
  record.request_scan = scans_;
  record.hypothesis.id = request.id;
  record.hypothesis.t_s = t_s;
  if (target_m) record.hypothesis.target_m = *target_m;
  records_.push_back(std::move(record));
  in_flight_record_ = request.id;
  in_flight_ = std::async(std::launch::async, [predictor = predictor_, request]() {
    return predictor(request);
  });
  updates_since_request_ = 0;
}

// With a deterministic schedule a result is taken at its scan exactly (waiting if need be) and
// never before; otherwise as soon as it is ready.
void PredictiveGridSlam::TakeFinished(bool wait) {
  if (!in_flight_.valid()) return;
  const int due = records_[in_flight_record_].request_scan + params_.deterministic_delay_scans;
  if (params_.deterministic_delay_scans > 0) {
    if (!wait && scans_ < due) return;
  } else if (!wait &&
             in_flight_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    return;
  }
  std::optional<PredictedStructure> result = in_flight_.get();
  HypothesisRecord& record = records_[in_flight_record_];
  record.install_scan = scans_;
  if (!result || !result->structure_found) {
    record.fate = HypothesisFate::kNoStructure;
    if (result) record.hypothesis.target_m = result->hypothesis.target_m;
  } else {
    const double t_s = record.hypothesis.t_s;  // the request's, whatever the predictor says
    record.hypothesis = std::move(result->hypothesis);
    record.hypothesis.id = in_flight_record_;
    record.hypothesis.t_s = t_s;
    record.fate = result->accepted ? HypothesisFate::kActive : HypothesisFate::kBelowThreshold;
    record.unexplored_cells = record.hypothesis.predicted_cells;
    if (result->accepted) Install(in_flight_record_);
  }
  in_flight_record_ = -1;
  if (queued_target_) {
    const Eigen::Vector2d target = *queued_target_;
    queued_target_.reset();
    Submit(target, last_t_s_);
  }
}

// Each particle sees h moved by its pose relative to the best particle's (seed Section IV).
void PredictiveGridSlam::Install(int record) {
  const int n = rbpf_.particle_count();
  const Pose2 best_inverse = rbpf_.particle(rbpf_.BestParticle()).pose.Inverse();
  Active active{record, std::vector<Pose2>(n), std::vector<HypothesisSupport>(n)};
  for (int i = 0; i < n; ++i) active.to_particle[i] = rbpf_.particle(i).pose.Compose(best_inverse);
  active_.push_back(std::move(active));
  RebuildLayers();
}

// After an update: recovery on this update's support (indices before resampling), then the
// transforms follow the resampled particles, then validation against the best map.
void PredictiveGridSlam::AfterUpdate() {
  bool changed = false;
  for (std::size_t k = active_.size(); k-- > 0;) {
    if (DropUnsupported(active_[k])) {
      Retire(k, HypothesisFate::kDroppedByRecovery);
      changed = true;
    }
  }
  const int n = rbpf_.particle_count();
  for (Active& active : active_) {
    std::vector<Pose2> moved(n);
    for (int i = 0; i < n; ++i) moved[i] = active.to_particle[rbpf_.particle_source(i)];
    active.to_particle = std::move(moved);
  }
  const int best = rbpf_.BestParticle();
  for (std::size_t k = active_.size(); k-- > 0;) {
    HypothesisRecord& record = records_[active_[k].record];
    record.unexplored_cells = UnexploredCells(record.hypothesis.cells,
                                              active_[k].to_particle[best], rbpf_.BestMap());
    if (record.unexplored_cells <
        params_.retire_below_unexplored_fraction * record.hypothesis.predicted_cells) {
      Retire(k, HypothesisFate::kExplored);
      changed = true;
    }
  }
  if (changed) RebuildLayers();
  if (params_.automatic_targets && !in_flight_.valid() &&
      ++updates_since_request_ >= params_.request_every_updates) {
    Submit(std::nullopt, last_t_s_);
  }
}

// SPEC S4 (c): dropped when some particle measured it on enough beams and none of those
// particles' hit ratio reached hr_th.
bool PredictiveGridSlam::DropUnsupported(Active& active) {
  bool measured = false, supported = false;
  HypothesisRecord& record = records_[active.record];
  for (const HypothesisSupport& s : active.support) {
    if (s.beams < params_.min_support_beams) continue;
    measured = true;
    record.best_hit_ratio = std::max(record.best_hit_ratio, s.HitRatio());
    supported = supported || s.HitRatio() >= params_.hit_ratio_threshold;
  }
  return params_.recovery && measured && !supported;
}

void PredictiveGridSlam::Retire(std::size_t index, HypothesisFate fate) {
  HypothesisRecord& record = records_[active_[index].record];
  record.fate = fate;
  record.end_scan = scans_;
  active_.erase(active_.begin() + static_cast<std::ptrdiff_t>(index));
}

// Particles with the same transforms (copies of one particle) share one layer.
void PredictiveGridSlam::RebuildLayers() {
  const int n = rbpf_.particle_count();
  std::vector<std::shared_ptr<const OccupancyGrid>> layers(n);
  for (int i = 0; i < n; ++i) {
    if (active_.empty()) continue;
    for (int j = 0; j < i && !layers[i]; ++j) {
      bool same = true;
      for (const Active& a : active_) {
        same = same && a.to_particle[i].vector() == a.to_particle[j].vector();
      }
      if (same) layers[i] = layers[j];
    }
    if (layers[i]) continue;
    auto layer = std::make_shared<OccupancyGrid>(rbpf_.particle(i).map.params());
    for (const Active& a : active_) {
      AddMovedHypothesis(records_[a.record].hypothesis.cells, a.to_particle[i], *layer);
    }
    layers[i] = std::move(layer);
  }
  for (int i = 0; i < n; ++i) rbpf_.SetSecondLayer(i, layers[i]);
}

const OccupancyGrid* PredictiveGridSlam::BestPredictedLayer() const {
  if (rbpf_.particle_count() == 0) return nullptr;
  return rbpf_.particle(rbpf_.BestParticle()).second_layer.get();
}

}  // namespace slamkit
