// SPEC S3: what reaches each vehicle of the fleet.
#include <algorithm>
#include <numeric>

#include "slamkit/sim/fleet.hpp"

namespace slamkit {
namespace {

// The end of the message starting at event `i`: the sender's sightings at that time.
std::size_t MessageEnd(const FleetLog& log, std::size_t i) {
  std::size_t j = i;
  while (j < log.events.size() && log.events[j].kind != FleetEvent::Kind::kControl &&
         log.events[j].vehicle == log.events[i].vehicle && log.events[j].t_s == log.events[i].t_s) {
    ++j;
  }
  return j;
}

// The message's events that fit the cap: the nearest ones, in log order.
void KeepNearest(const FleetLog& log, std::size_t begin, std::size_t end, int cap,
                 std::vector<int>* out) {
  std::vector<int> message(end - begin);
  std::iota(message.begin(), message.end(), static_cast<int>(begin));
  if (cap > 0 && static_cast<int>(message.size()) > cap) {
    std::stable_sort(message.begin(), message.end(), [&log](int a, int b) {
      return log.events[a].value.x() < log.events[b].value.x();
    });
    message.resize(cap);
    std::sort(message.begin(), message.end());
  }
  out->insert(out->end(), message.begin(), message.end());
}

}  // namespace

std::vector<int> DeliveredEvents(const FleetLog& log, int receiver, const MessageParams& params,
                                 Rng& rng) {
  std::vector<int> delivered;
  for (std::size_t i = 0; i < log.events.size();) {
    const FleetEvent& e = log.events[i];
    if (e.vehicle == receiver || e.kind == FleetEvent::Kind::kControl) {
      delivered.push_back(static_cast<int>(i++));
      continue;
    }
    const std::size_t end = MessageEnd(log, i);
    const bool lost = params.loss_probability > 0.0 && rng.Uniform() < params.loss_probability;
    if (!lost) KeepNearest(log, i, end, params.max_sightings, &delivered);
    i = end;
  }
  return delivered;
}

}  // namespace slamkit
