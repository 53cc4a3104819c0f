// A cooperative filter behind real time, for delayed messages (coop_run.cpp).
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "slamkit/core/fleet_log.hpp"
#include "slamkit/models/unicycle.hpp"
#include "slamkit/runners/cooperative/coop_run.hpp"

namespace slamkit::internal {

struct PoseNow {
  double t_s = 0.0;
  Pose2 pose;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

// The control noise of one interval, as the filters use it (a density when the config gives one).
ControlCovariance ControlNoise(const CoopFilterParams& p, const Control& u, double dt_s);

// `x` moved on by control u held for dt_s (nothing for dt_s <= 0), its covariance propagated as
// the filters predict.
void Step(const UnicycleModel& model, const CoopFilterParams& p, const Control& u, double dt_s,
          PoseNow* x);

// With messages up to `lag_s` late, vehicle `self`'s filter takes the events of time t when
// real time reaches t + lag_s, every message about t being in hand then. Its estimate at real
// time t + lag_s is its pose block at t (`pose`, `covariance`) moved on by its own controls of
// (t, t + lag_s], which it has by then: `u` from t, then each later control event of `self` in
// events[next...] (indices into log.events, in time order). The marginal of the pose block is
// propagated exactly as the filter would (the same model and control noise).
PoseNow MoveOnByOwnControls(const FleetLog& log, const std::vector<int>& events, std::size_t next,
                            int self, const PoseNow& at_t, const Control& u, double lag_s,
                            const CoopFilterParams& p);

}  // namespace slamkit::internal
