// SPEC S3: one estimator of a cooperative run over a fleet's recording.
#include "slamkit/runners/cooperative/coop_run.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <stdexcept>
#include <utility>

#include "coop_lag.hpp"
#include "coop_scoring.hpp"
#include "coop_smoothed.hpp"
#include "slamkit/eval/errors.hpp"

namespace slamkit {
namespace {

using internal::DeadReckoning;
using internal::Record;
using internal::Summarise;

using Clock = std::chrono::steady_clock;

// One filter and where each of its vehicles' pose blocks is in time.
struct Estimator {
  std::unique_ptr<CooperativeEkfSlam> filter;
  std::vector<double> time_s;
  std::vector<Control> control;  // the latest control of each vehicle (empty: none yet)
  std::vector<LandmarkId> landmark_truth;  // by landmark index: its creating sighting's truth
  std::vector<std::pair<int, LandmarkId>> assigned;  // (landmark, true id) of each used sighting
  std::vector<double> last_record_s;
  int self = -1;      // the vehicle whose filter this is (-1: the central filter)
  Trajectory* own_path = nullptr;  // when set, gets self's pose at each of its controls
  double lag_s = 0.0;  // how far behind real time it runs (delayed messages)
};

CooperativeMode FilterModeOf(CoopMode mode) {
  switch (mode) {
    case CoopMode::kMono: return CooperativeMode::kMono;
    case CoopMode::kExtended: return CooperativeMode::kExtended;
    default: return CooperativeMode::kExact;
  }
}

Estimator MakeEstimator(const FleetLog& log, CoopMode mode, int self, const CoopFilterParams& p) {
  CooperativeEkfSlamParams fp = p.filter;
  fp.mode = FilterModeOf(mode);
  if (p.known_association) fp.ekf.association_method = AssociationMethod::kKnown;
  if (!p.known_association && fp.ekf.association_method == AssociationMethod::kKnown) {
    // The sightings carry no ids then: every one would start a landmark.
    throw std::invalid_argument("coop: known association is off but the associator is 'known'");
  }
  Estimator e;
  std::unique_ptr<Associator> associator =
      p.known_association ? std::make_unique<KnownAssociation>(p.known_gate_chi2)
                          : MakeAssociator(fp.ekf);
  e.filter = std::make_unique<CooperativeEkfSlam>(fp, log.vehicles, self,
                                                  std::make_unique<UnicycleModel>(p.motion),
                                                  std::make_unique<RangeBearingModel>(p.sensor),
                                                  std::move(associator));
  e.filter->Reset(log.start_poses);
  const double t0 = log.events.empty() ? 0.0 : log.events.front().t_s;
  e.time_s.assign(log.vehicles, t0);
  e.control.assign(log.vehicles, Control());
  e.last_record_s.assign(log.vehicles, -1e300);
  e.self = self;
  // Only filters that take other vehicles' messages wait for them; Mono and the central
  // filter (the reference: every measurement once, as soon as it is made) do not.
  const bool receives = mode == CoopMode::kExtended || mode == CoopMode::kExact;
  e.lag_s = self >= 0 && receives ? p.messages.delay_s : 0.0;
  return e;
}

// Moves vehicle v's block to time t with its latest control (none yet: it stands still).
void Advance(Estimator& e, int v, double t, const CoopFilterParams& p) {
  if (!e.filter->Tracks(v) || t <= e.time_s[v]) return;
  const double dt = t - e.time_s[v];
  if (e.control[v].size() > 0) {
    const ControlCovariance Q = internal::ControlNoise(p, e.control[v], dt);
    e.filter->Predict(v, e.control[v], dt, &Q);
  }
  e.time_s[v] = t;
}

LandmarkId TrueId(const FleetLog& log, const std::vector<LandmarkId>& true_ids, int event) {
  return true_ids.empty() ? log.events[event].landmark : true_ids[event];
}

// The scan made of the sightings from events[begin] on that share its vehicle and time.
FleetScan ScanAt(const FleetLog& log, const std::vector<int>& events, std::size_t begin,
                 std::size_t* end, const std::vector<LandmarkId>& true_ids,
                 const CoopFilterParams& p, std::vector<int>* landmark_events) {
  const FleetEvent& first = log.events[events[begin]];
  FleetScan scan;
  scan.vehicle = first.vehicle;
  scan.t_s = first.t_s;
  const RangeBearingModel sensor(p.sensor), vehicle_sensor(p.vehicle_sensor);
  std::size_t i = begin;
  for (; i < events.size(); ++i) {
    const FleetEvent& e = log.events[events[i]];
    if (e.kind == FleetEvent::Kind::kControl || e.vehicle != first.vehicle || e.t_s != first.t_s) {
      break;
    }
    if (e.kind == FleetEvent::Kind::kVehicleSighting) {
      scan.vehicles.push_back({e.target, e.value, vehicle_sensor.NoiseCovariance()});
      continue;
    }
    const LandmarkId id = p.known_association ? TrueId(log, true_ids, events[i]) : kNoLandmark;
    scan.landmarks.push_back({e.value, sensor.NoiseCovariance(), id});
    landmark_events->push_back(events[i]);
  }
  *end = i;
  return scan;
}


// Runs `e` over `events` (indices into log.events, in order), recording the vehicles `recorded`.
void Process(const FleetLog& log, const FleetTruth& truth, const std::vector<LandmarkId>& true_ids,
             const std::vector<int>& events, const std::vector<char>& recorded,
             const CoopFilterParams& p, Estimator& e, CoopModeResult* out, double* update_s) {
  for (std::size_t j = 0; j < events.size();) {
    const FleetEvent& ev = log.events[events[j]];
    if (ev.kind == FleetEvent::Kind::kControl) {
      const int v = ev.vehicle;
      Advance(e, v, ev.t_s, p);
      if (e.own_path != nullptr && v == e.self) {
        e.own_path->push_back({ev.t_s, e.filter->PoseOf(v)});
      }
      e.control[v] = Control(2);
      e.control[v] << ev.value.x(), ev.value.y();
      if (recorded[v] && e.filter->Tracks(v) && ev.t_s - e.last_record_s[v] >= p.record_period_s) {
        internal::PoseNow now{ev.t_s, e.filter->PoseOf(v), e.filter->PoseCovarianceOf(v)};
        if (v == e.self && e.lag_s > 0.0) {
          now = internal::MoveOnByOwnControls(log, events, j + 1, v, now, e.control[v], e.lag_s, p);
        }
        if (Record(out->vehicles[v], now.t_s, now.pose, now.covariance, truth.paths[v])) {
          e.last_record_s[v] = ev.t_s;
        }
      }
      ++j;
      continue;
    }
    std::vector<int> landmark_events;
    std::size_t end = j;
    const FleetScan scan = ScanAt(log, events, j, &end, true_ids, p, &landmark_events);
    j = end;
    for (int v = 0; v < log.vehicles; ++v) Advance(e, v, scan.t_s, p);
    const auto start = Clock::now();
    const std::vector<AssociationDecision> decisions = e.filter->Update(scan);
    *update_s += std::chrono::duration<double>(Clock::now() - start).count();
    ++out->scans;
    for (std::size_t k = 0; k < decisions.size(); ++k) {
      if (decisions[k].kind == AssociationDecision::Kind::kDropped) continue;
      const LandmarkId true_id = TrueId(log, true_ids, landmark_events[k]);
      if (true_id != kNoLandmark) e.assigned.emplace_back(decisions[k].landmark, true_id);
      if (decisions[k].kind != AssociationDecision::Kind::kNew) continue;
      const auto l = static_cast<std::size_t>(decisions[k].landmark);
      if (e.landmark_truth.size() <= l) e.landmark_truth.resize(l + 1, kNoLandmark);
      e.landmark_truth[l] = true_id;
    }
  }
}

// Among events of one time, the receiver's own first: its sensing at t is in hand before any
// message about t can arrive. The seed's extended observations need it: vehicle b's shared scan
// at t is extended through the receiver's own v-v sighting of b at t, which the log may list
// after b's scan (the simulator lists vehicle 0 first, so vehicle 1 never extended a thing).
void OwnEventsFirstAtEachTime(const FleetLog& log, int self, std::vector<int>* events) {
  std::stable_sort(events->begin(), events->end(), [&](int a, int b) {
    const FleetEvent& x = log.events[a];
    const FleetEvent& y = log.events[b];
    if (x.t_s != y.t_s) return x.t_s < y.t_s;
    return x.vehicle == self && y.vehicle != self;
  });
}

void AddCounts(const CooperativeEkfSlam::Counts& c, CooperativeEkfSlam::Counts* sum) {
  sum->vehicle_updates += c.vehicle_updates;
  sum->vehicle_gated += c.vehicle_gated;
  sum->extended += c.extended;
  sum->landmark_updates += c.landmark_updates;
  sum->landmark_dropped += c.landmark_dropped;
}

// CoopMode::kMonoSmoothed: each vehicle's Mono filter gives its smoother the start.
CoopModeResult MonoSmoothed(const FleetLog& log, const FleetTruth& truth,
                            const std::vector<LandmarkId>& true_ids, const CoopFilterParams& p,
                            std::uint64_t message_seed) {
  CoopModeResult out;
  out.mode = CoopMode::kMonoSmoothed;
  out.vehicles.resize(log.vehicles);
  for (int v = 0; v < log.vehicles; ++v) {
    Estimator e = MakeEstimator(log, CoopMode::kMono, v, p);
    Trajectory filtered;
    e.own_path = &filtered;
    Rng rng(message_seed + static_cast<std::uint64_t>(v));
    CoopModeResult unrecorded;
    double update_s = 0.0;
    Process(log, truth, true_ids, DeliveredEvents(log, v, p.messages, rng),
            std::vector<char>(log.vehicles, 0), p, e, &unrecorded, &update_s);
    const internal::MonoSmoothing s = internal::SmoothMonoVehicle(log, true_ids, v, filtered, p);
    CoopVehicleTrace& trace = out.vehicles[v];
    double last_s = -1e300;
    for (const StampedPose& pose : s.path) {
      if (pose.t_s - last_s >= p.record_period_s &&
          Record(trace, pose.t_s, pose.pose, Eigen::Matrix3d::Zero(), truth.paths[v])) {
        last_s = pose.t_s;
      }
    }
    trace.map = s.map;
    trace.counts.landmark_updates = s.sightings_used;
    trace.counts.landmark_dropped = s.sightings_dropped;
    Summarise(trace, truth.world, s.landmark_truth);
    AddCounts(trace.counts, &out.counts);
  }
  return out;
}

}  // namespace

std::string_view CoopModeName(CoopMode mode) {
  switch (mode) {
    case CoopMode::kDeadReckoning: return "dead-reckoning";
    case CoopMode::kMono: return "mono";
    case CoopMode::kExtended: return "eo";
    case CoopMode::kExact: return "eo-exact";
    case CoopMode::kCentral: return "central";
    case CoopMode::kMonoSmoothed: return "mono-smoothed";
  }
  return "unknown";
}

std::optional<CoopMode> CoopModeFromName(std::string_view name) {
  for (const CoopMode m : {CoopMode::kDeadReckoning, CoopMode::kMono, CoopMode::kExtended,
                           CoopMode::kExact, CoopMode::kCentral, CoopMode::kMonoSmoothed}) {
    if (CoopModeName(m) == name) return m;
  }
  return std::nullopt;
}

bool HasCovariance(CoopMode mode) {
  return mode != CoopMode::kDeadReckoning && mode != CoopMode::kMonoSmoothed;
}

CoopModeResult RunCoopMode(const FleetLog& log, const FleetTruth& truth,
                           const std::vector<LandmarkId>& true_ids, CoopMode mode,
                           const CoopFilterParams& params, std::uint64_t message_seed) {
  if (mode == CoopMode::kDeadReckoning) return DeadReckoning(log, truth, params);
  if (mode == CoopMode::kMonoSmoothed) {
    return MonoSmoothed(log, truth, true_ids, params, message_seed);
  }
  CoopModeResult out;
  out.mode = mode;
  out.vehicles.resize(log.vehicles);
  double update_s = 0.0;
  const int filters = mode == CoopMode::kCentral ? 1 : log.vehicles;
  for (int f = 0; f < filters; ++f) {
    const int self = mode == CoopMode::kCentral ? -1 : f;
    Estimator e = MakeEstimator(log, mode, self, params);
    std::vector<int> events;
    if (self < 0) {
      events.resize(log.events.size());
      for (std::size_t i = 0; i < events.size(); ++i) events[i] = static_cast<int>(i);
    } else {
      Rng rng(message_seed + static_cast<std::uint64_t>(self));
      events = DeliveredEvents(log, self, params.messages, rng);
      // Only EO looks up an earlier measurement (its latest v-v sighting); the exact mode uses
      // each one once on its own blocks, in the log's order, as the central filter does.
      if (mode == CoopMode::kExtended) OwnEventsFirstAtEachTime(log, self, &events);
    }
    std::vector<char> recorded(log.vehicles, self < 0 ? 1 : 0);
    if (self >= 0) recorded[self] = 1;
    Process(log, truth, true_ids, events, recorded, params, e, &out, &update_s);
    e.filter->CheckOutputHealth();
    AddCounts(e.filter->counts(), &out.counts);
    const LandmarkMap map = e.filter->Map();
    const double agreement =
        e.assigned.empty()
            ? -1.0
            : AssociationAgreement(e.assigned, static_cast<int>(e.assigned.size())).share;
    for (int v = 0; v < log.vehicles; ++v) {
      if (!recorded[v]) continue;
      out.vehicles[v].map = map;
      out.vehicles[v].association_agreement = agreement;
      out.vehicles[v].counts = e.filter->counts();
      Summarise(out.vehicles[v], truth.world, e.landmark_truth);
    }
  }
  out.update_time_mean_s = out.scans > 0 ? update_s / double(out.scans) : 0.0;
  return out;
}

}  // namespace slamkit
