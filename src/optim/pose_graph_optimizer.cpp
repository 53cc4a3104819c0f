// SE(2) pose-graph optimisation on Ceres.
#include "slamkit/optim/pose_graph_optimizer.hpp"

#include <chrono>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <ceres/covariance.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include "pose_graph_index.hpp"
#include "slamkit/optim/pose_graph_factors.hpp"

namespace slamkit {
namespace {

template <class Factor>
double EdgeObjective(const PoseGraphEdge& e, const Pose2& from, const Pose2& to) {
  const Eigen::Vector3d xi = from.vector(), xj = to.vector();
  const double* parameters[] = {xi.data(), xj.data()};
  Eigen::Vector3d r;
  Factor(e).Evaluate(parameters, r.data(), nullptr);
  return r.squaredNorm();
}

template <class Factor>
double Objective(const PoseGraph& graph, const std::vector<Pose2>& poses) {
  if (poses.size() != graph.vertices.size()) {
    throw std::invalid_argument("pose graph: one pose per vertex is needed");
  }
  const internal::VertexIndex index(graph);
  double sum = 0.0;
  for (const PoseGraphEdge& e : graph.edges) {
    sum += EdgeObjective<Factor>(e, poses[index(e.from)], poses[index(e.to)]);
  }
  return sum;
}

ceres::CostFunction* MakeFactor(const PoseGraphEdge& e, PoseGraphObjective objective) {
  if (objective == PoseGraphObjective::kSeSync) return new RelativePoseSeSyncFactor(e);
  return new RelativePoseChi2Factor(e);
}

ceres::Solver::Options SolverOptions(const PoseGraphOptimizerParams& p) {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  options.max_num_iterations = p.max_iterations;
  options.function_tolerance = p.function_tolerance;
  options.gradient_tolerance = p.gradient_tolerance;
  options.parameter_tolerance = p.parameter_tolerance;
  options.num_threads = std::max(1, p.threads);
  options.logging_type = ceres::SILENT;
  return options;
}

// The problem over `x` (set to `initial`): one factor per edge, closures with the robust loss,
// the first vertex constant (the gauge).
void BuildProblem(const PoseGraph& graph, const std::vector<Pose2>& initial,
                  const PoseGraphOptimizerParams& params, std::vector<Eigen::Vector3d>* x,
                  ceres::Problem* problem) {
  if (initial.size() != graph.vertices.size()) {
    throw std::invalid_argument("pose graph: one pose per vertex is needed");
  }
  const internal::VertexIndex index(graph);
  x->clear();
  x->reserve(initial.size());
  for (const Pose2& p : initial) x->push_back(p.vector());
  for (const PoseGraphEdge& e : graph.edges) {
    const int i = index(e.from), j = index(e.to);
    ceres::LossFunction* loss =
        std::abs(i - j) == 1 ? nullptr : MakeRobustLoss(params.loop_closure_loss).release();
    problem->AddResidualBlock(MakeFactor(e, params.objective), loss, (*x)[i].data(),
                              (*x)[j].data());
  }
  if (!x->empty() && problem->HasParameterBlock(x->front().data())) {
    problem->SetParameterBlockConstant(x->front().data());
  }
}

}  // namespace

std::vector<Pose2> InitialPoses(const PoseGraph& graph) {
  std::vector<Pose2> poses;
  poses.reserve(graph.vertices.size());
  for (const PoseGraphVertex& v : graph.vertices) poses.push_back(v.pose);
  return poses;
}

double Chi2(const PoseGraph& graph, const std::vector<Pose2>& poses) {
  return Objective<RelativePoseChi2Factor>(graph, poses);
}

double EdgeChi2(const PoseGraphEdge& edge, const Pose2& from, const Pose2& to) {
  return EdgeObjective<RelativePoseChi2Factor>(edge, from, to);
}

double SeSyncObjective(const PoseGraph& graph, const std::vector<Pose2>& poses) {
  return Objective<RelativePoseSeSyncFactor>(graph, poses);
}

PoseGraphSolution OptimizePoseGraph(const PoseGraph& graph, const std::vector<Pose2>& initial,
                                    const PoseGraphOptimizerParams& params) {
  const auto start = std::chrono::steady_clock::now();
  PoseGraphSolution solution;
  solution.initial_chi2 = Chi2(graph, initial);
  solution.initial_sesync_objective = SeSyncObjective(graph, initial);
  std::vector<Eigen::Vector3d> x;
  ceres::Problem problem;
  BuildProblem(graph, initial, params, &x, &problem);
  ceres::Solver::Summary summary;
  ceres::Solve(SolverOptions(params), &problem, &summary);
  for (const Eigen::Vector3d& v : x) solution.poses.emplace_back(v);
  solution.chi2 = Chi2(graph, solution.poses);
  solution.sesync_objective = SeSyncObjective(graph, solution.poses);
  solution.iterations = static_cast<int>(summary.iterations.size()) - 1;
  solution.converged = summary.termination_type == ceres::CONVERGENCE;
  solution.termination = summary.message;
  solution.time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return solution;
}

std::vector<Eigen::Matrix3d> MarginalCovariances(const PoseGraph& graph,
                                                 const std::vector<Pose2>& poses,
                                                 const std::vector<int>& vertex_ids,
                                                 const PoseGraphOptimizerParams& params) {
  std::vector<Eigen::Vector3d> x;
  ceres::Problem problem;
  BuildProblem(graph, poses, params, &x, &problem);
  const internal::VertexIndex index(graph);
  std::vector<std::pair<const double*, const double*>> blocks;
  for (const int id : vertex_ids) {
    const double* block = x[index(id)].data();
    if (index(id) == 0) continue;
    if (!problem.HasParameterBlock(block)) {
      throw std::invalid_argument("pose graph: no edge reaches vertex " + std::to_string(id));
    }
    blocks.emplace_back(block, block);
  }
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::SPARSE_QR;
  ceres::Covariance covariance(options);
  if (!blocks.empty() && !covariance.Compute(blocks, &problem)) {
    throw std::invalid_argument("pose graph: the information is singular at these poses");
  }
  std::vector<Eigen::Matrix3d> out;
  for (const int id : vertex_ids) {
    Eigen::Matrix<double, 3, 3, Eigen::RowMajor> C = Eigen::Matrix3d::Zero();
    if (index(id) != 0) covariance.GetCovarianceBlock(x[index(id)].data(), x[index(id)].data(), C.data());
    out.emplace_back(C);
  }
  return out;
}

}  // namespace slamkit
