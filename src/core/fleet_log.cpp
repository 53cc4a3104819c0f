#include "slamkit/core/fleet_log.hpp"

#include <algorithm>

namespace slamkit {

void OrderFleetEvents(std::vector<FleetEvent>& events) {
  std::stable_sort(events.begin(), events.end(), [](const FleetEvent& a, const FleetEvent& b) {
    const bool a_control = a.kind == FleetEvent::Kind::kControl;
    const bool b_control = b.kind == FleetEvent::Kind::kControl;
    if (a.t_s != b.t_s) return a.t_s < b.t_s;
    if (a_control != b_control) return b_control;
    return a.vehicle < b.vehicle;
  });
}

}  // namespace slamkit
