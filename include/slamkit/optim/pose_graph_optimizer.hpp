#pragma once

#include <string>
#include <vector>

#include "slamkit/core/pose_graph.hpp"
#include "slamkit/optim/robust_loss.hpp"

namespace slamkit {

// What the optimiser minimises over a pose graph.
enum class PoseGraphObjective {
  kChi2,    // g2o's χ²: Σ eᵀ Ω e (RelativePoseChi2Factor)
  kSeSync,  // SE-Sync's objective, Rosen et al. 2019, Eq. 12 (RelativePoseSeSyncFactor)
};

struct PoseGraphOptimizerParams {
  PoseGraphObjective objective = PoseGraphObjective::kChi2;
  int max_iterations = 500;
  // Levenberg-Marquardt stops when the cost's relative decrease, the gradient's max norm or
  // the step's relative size falls below these (Ceres' tolerances).
  double function_tolerance = 1e-12;
  double gradient_tolerance = 1e-12;
  double parameter_tolerance = 1e-12;
  int threads = 1;
  // The loss of loop closures: edges whose vertices are not consecutive in the graph's vertex
  // order (consecutive ones are odometry and keep the plain squared loss).
  RobustLossParams loop_closure_loss;
};

struct PoseGraphSolution {
  std::vector<Pose2> poses;  // in the graph's vertex order
  double chi2 = 0.0;         // g2o's χ² at the solution
  double sesync_objective = 0.0;
  double initial_chi2 = 0.0;
  double initial_sesync_objective = 0.0;
  int iterations = 0;
  bool converged = false;
  std::string termination;  // Ceres' message
  double time_s = 0.0;
};

// Minimises `params.objective` from `initial` (one pose per vertex, in vertex order) by
// Levenberg-Marquardt with sparse Cholesky, the first vertex held fixed (the gauge). Throws
// std::invalid_argument for a size mismatch, an edge naming an unknown vertex, or an information
// matrix that is not positive definite.
PoseGraphSolution OptimizePoseGraph(const PoseGraph& graph, const std::vector<Pose2>& initial,
                                    const PoseGraphOptimizerParams& params = {});

// The marginal covariances (x, y, θ) of the vertices `vertex_ids` at `poses` (a solution), from
// the Gauss-Newton information of the same problem (robust losses as in `params`), the first
// vertex fixed: its covariance is zero. Throws std::invalid_argument when the information is
// singular (a vertex no edge reaches).
std::vector<Eigen::Matrix3d> MarginalCovariances(const PoseGraph& graph,
                                                 const std::vector<Pose2>& poses,
                                                 const std::vector<int>& vertex_ids,
                                                 const PoseGraphOptimizerParams& params = {});

// The files' initial values, in vertex order.
std::vector<Pose2> InitialPoses(const PoseGraph& graph);

// Chordal initialisation (rotation first; Carlone et al. 2015, as SE-Sync starts): the
// rotations as unit complex numbers relaxed to the plane and solved by linear least squares
// weighted by κ, projected back to angles; then the translations by linear least squares weighted
// by τ given those rotations. The first vertex keeps its initial pose.
std::vector<Pose2> ChordalInitialization(const PoseGraph& graph);

double Chi2(const PoseGraph& graph, const std::vector<Pose2>& poses);
// One edge's term of Chi2: eᵀ Ω e with `from` and `to` its vertices' poses.
double EdgeChi2(const PoseGraphEdge& edge, const Pose2& from, const Pose2& to);
double SeSyncObjective(const PoseGraph& graph, const std::vector<Pose2>& poses);

}  // namespace slamkit
