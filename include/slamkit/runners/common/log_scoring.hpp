#pragma once

// How a run on a laser log is scored, whatever filter ran: against the log's relations
// (Kümmerle et al.) and reference poses, beside the log's raw odometry, the baseline every
// estimate must beat; and the metrics.json keys of those scores.

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "slamkit/core/relation.hpp"
#include "slamkit/core/trajectory.hpp"
#include "slamkit/eval/heading_drift.hpp"
#include "slamkit/eval/trajectory_errors.hpp"
#include "slamkit/io/carmen_reader.hpp"

namespace slamkit {

// The evaluations after a run, of the estimate and of the log's raw odometry. A failing one is
// recorded in `error`, never allowed to lose the run's outputs.
struct LogEvaluation {
  std::optional<RelationErrorStats> relations;
  std::optional<ReferenceComparison> reference;
  std::optional<RelationErrorStats> odometry_relations;
  std::optional<ReferenceComparison> odometry_reference;
  std::string error;
};

struct LogScoringParams {
  PairBy pair_by = PairBy::kTime;  // how reference poses pair with the estimate's
  // The run covered part of the log only (a scan limit): relations beyond it are not scored.
  bool partial_log = false;
};

// Scores `estimate` and `odometry` (one pose per scan) against `relations` (none: not scored)
// and `reference` (unset: not scored). A run that stopped early is scored on what it covered.
LogEvaluation EvaluateOnLog(const Trajectory& estimate, const Trajectory& odometry,
                            std::vector<PoseRelation> relations,
                            const std::optional<Trajectory>& reference,
                            const LogScoringParams& params);

// The error keys of metrics.json (relations_*, ate_*, rpe_*) for the evaluations given (either
// may be null).
void AddErrorMetrics(const RelationErrorStats* relations, const ReferenceComparison* reference,
                     nlohmann::json& metrics);
// The odometry baseline's keys (odometry_relations_*, odometry_ate_rmse_m, odometry_rpe_*) and
// a failed evaluation's `evaluation_error`.
void AddBaselineMetrics(const LogEvaluation& evaluation, nlohmann::json& metrics);

// The poses a log gives with its scans (corrected in *-corrected logs), one per scan.
Trajectory LoggedTrajectory(const CarmenLog& log);
// The raw odometry at each scan: the baseline every estimate must beat.
Trajectory OdometryTrajectory(const CarmenLog& log);

// Peak resident memory of this process so far, in MiB.
double PeakRssMib();

// metrics.json's odometry_heading_drift of an iSAM or grid run.
nlohmann::json HeadingDriftJson(const HeadingDriftFit& fit, const HeadingDriftParams& params);

}  // namespace slamkit
