#include "coop_lag.hpp"

#include "slamkit/models/unicycle.hpp"

namespace slamkit::internal {

void Step(const UnicycleModel& model, const CoopFilterParams& p, const Control& u, double dt_s,
          PoseNow* x) {
  if (dt_s <= 0.0) return;
  Eigen::Matrix3d J_x;
  ControlJacobian J_u;
  x->pose = model.Move(x->pose, u, dt_s, &J_x, &J_u);
  const ControlCovariance Q = ControlNoise(p, u, dt_s);
  x->covariance = J_x * x->covariance * J_x.transpose() + J_u * Q * J_u.transpose();
  x->t_s += dt_s;
}

ControlCovariance ControlNoise(const CoopFilterParams& p, const Control& u, double dt_s) {
  if (!p.control_noise_density) return UnicycleModel(p.motion).Noise(u, dt_s);
  ControlCovariance Q = ControlCovariance::Zero(2, 2);
  Q(0, 0) = p.control_noise_density->x() / dt_s;
  Q(1, 1) = p.control_noise_density->y() / dt_s;
  return Q;
}

PoseNow MoveOnByOwnControls(const FleetLog& log, const std::vector<int>& events, std::size_t next,
                            int self, const PoseNow& at_t, const Control& u, double lag_s,
                            const CoopFilterParams& p) {
  const UnicycleModel model(p.motion);
  const double end_s = at_t.t_s + lag_s;
  PoseNow x = at_t;
  Control current = u;
  for (std::size_t k = next; k < events.size(); ++k) {
    const FleetEvent& e = log.events[events[k]];
    if (e.t_s > end_s) break;
    if (e.kind != FleetEvent::Kind::kControl || e.vehicle != self) continue;
    Step(model, p, current, e.t_s - x.t_s, &x);
    x.t_s = e.t_s;  // exactly the event's time, whatever the sum of the steps rounded to
    current << e.value.x(), e.value.y();
  }
  Step(model, p, current, end_s - x.t_s, &x);
  x.t_s = end_s;
  return x;
}

}  // namespace slamkit::internal
