// Chordal initialisation of a 2D pose graph (rotations first, then translations).
#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>

#include "pose_graph_index.hpp"
#include "slamkit/optim/pose_graph_factors.hpp"
#include "slamkit/optim/pose_graph_optimizer.hpp"

namespace slamkit {
namespace {

using Triplets = std::vector<Eigen::Triplet<double>>;

// Solves min |A x − b|² over the 2-vectors of every vertex but the first (whose value `fixed`
// moves to the right-hand side). Each row block: w (x_j − M x_i − c) for an edge (i, j).
struct PlanarLeastSquares {
  int unknowns;
  Triplets triplets;
  std::vector<double> rhs;
  Eigen::Vector2d fixed;

  void AddTerm(int row, int vertex, const Eigen::Matrix2d& M, double w, Eigen::Vector2d* r) {
    if (vertex == 0) {
      *r -= w * M * fixed;
      return;
    }
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) triplets.emplace_back(row + a, 2 * (vertex - 1) + b, w * M(a, b));
    }
  }
  // Adds w (x_j − M x_i) = w c.
  void AddEdge(int i, int j, const Eigen::Matrix2d& M, const Eigen::Vector2d& c, double w) {
    const int row = static_cast<int>(rhs.size());
    Eigen::Vector2d r = w * c;
    AddTerm(row, j, Eigen::Matrix2d::Identity(), w, &r);
    AddTerm(row, i, M, -w, &r);
    rhs.push_back(r.x());
    rhs.push_back(r.y());
  }
  std::vector<Eigen::Vector2d> Solve(int vertices) const {
    Eigen::SparseMatrix<double> A(static_cast<int>(rhs.size()), unknowns);
    A.setFromTriplets(triplets.begin(), triplets.end());
    const Eigen::Map<const Eigen::VectorXd> b(rhs.data(), static_cast<int>(rhs.size()));
    const Eigen::SparseMatrix<double> AtA = A.transpose() * A;
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(AtA);
    const Eigen::VectorXd x = ldlt.solve(A.transpose() * b);
    if (ldlt.info() != Eigen::Success || !x.allFinite()) {
      throw std::invalid_argument("pose graph: chordal initialisation failed (is it connected?)");
    }
    std::vector<Eigen::Vector2d> out(vertices, fixed);
    for (int v = 1; v < vertices; ++v) out[v] = x.segment<2>(2 * (v - 1));
    return out;
  }
};

}  // namespace

std::vector<Pose2> ChordalInitialization(const PoseGraph& graph) {
  const int n = static_cast<int>(graph.vertices.size());
  if (n == 0) return {};
  const internal::VertexIndex index(graph);
  const Pose2 anchor = graph.vertices.front().pose;
  // Rotations as z = (cos θ, sin θ): z_j = R(θ_ij) z_i, relaxed to z in the plane.
  PlanarLeastSquares rotations{2 * (n - 1), {}, {}, {std::cos(anchor.theta()), std::sin(anchor.theta())}};
  for (const PoseGraphEdge& e : graph.edges) {
    const double w = std::sqrt(SeSyncWeightsOf(e).kappa);
    rotations.AddEdge(index(e.from), index(e.to), Eigen::Rotation2Dd(e.measurement.theta()).toRotationMatrix(),
                      Eigen::Vector2d::Zero(), w);
  }
  const std::vector<Eigen::Vector2d> z = rotations.Solve(n);
  std::vector<double> theta(n);
  for (int v = 0; v < n; ++v) theta[v] = std::atan2(z[v].y(), z[v].x());
  theta[0] = anchor.theta();
  // Translations given the rotations: t_j − t_i = R_i t_ij.
  PlanarLeastSquares translations{2 * (n - 1), {}, {}, anchor.translation()};
  for (const PoseGraphEdge& e : graph.edges) {
    const int i = index(e.from), j = index(e.to);
    const double w = std::sqrt(SeSyncWeightsOf(e).tau);
    translations.AddEdge(i, j, Eigen::Matrix2d::Identity(),
                         Eigen::Rotation2Dd(theta[i]).toRotationMatrix() * e.measurement.translation(), w);
  }
  const std::vector<Eigen::Vector2d> t = translations.Solve(n);
  std::vector<Pose2> poses;
  poses.reserve(n);
  for (int v = 0; v < n; ++v) poses.emplace_back(t[v].x(), t[v].y(), theta[v]);
  return poses;
}

}  // namespace slamkit
