#include "slamkit/optim/grid_scan_refinement.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include <ceres/autodiff_cost_function.h>
#include <ceres/cubic_interpolation.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

namespace slamkit {
namespace {

// The grid as Ceres' interpolators read it: 1 − P at cell (column x, row y), cell centres at
// integer coordinates. A table over the 256 stored values saves an exp per read.
class CorrespondenceCostGrid {
 public:
  enum { DATA_DIMENSION = 1 };
  CorrespondenceCostGrid(const OccupancyGrid& grid, double unknown_probability) : grid_(grid) {
    for (int v = -128; v < 128; ++v) {
      const auto steps = static_cast<OccupancyGrid::CellValue>(v);
      cost_[static_cast<std::size_t>(v + 128)] =
          1.0 - (v == 0 ? unknown_probability : OccupancyGrid::StepsProbability(steps));
    }
  }
  void GetValue(int row, int column, double* value) const {
    *value = cost_[static_cast<std::size_t>(grid_.LogOddsSteps({column, row}) + 128)];
  }

 private:
  const OccupancyGrid& grid_;
  std::array<double, 256> cost_{};
};

// Hess et al. 2016, Eq. (CS): one residual per point, w/√n · (1 − M_smooth(T_ξ h_k)).
struct OccupiedSpaceCost {
  OccupiedSpaceCost(const ceres::BiCubicInterpolator<CorrespondenceCostGrid>& map,
                    const std::vector<Eigen::Vector2d>& points, double weight,
                    double inverse_resolution)
      : map(map), points(points), weight(weight), inverse_resolution(inverse_resolution) {}

  template <typename T>
  bool operator()(const T* pose, T* residuals) const {
    const T c = cos(pose[2]), s = sin(pose[2]);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const T x = pose[0] + c * points[i].x() - s * points[i].y();
      const T y = pose[1] + s * points[i].x() + c * points[i].y();
      // Cell (i, j) holds the square [i, i + 1) × [j, j + 1) in cells: its centre is at +0.5.
      map.Evaluate(y * inverse_resolution - 0.5, x * inverse_resolution - 0.5, &residuals[i]);
      residuals[i] *= weight;
    }
    return true;
  }

  const ceres::BiCubicInterpolator<CorrespondenceCostGrid>& map;
  const std::vector<Eigen::Vector2d>& points;
  double weight;
  double inverse_resolution;
};

struct StayNearStartCost {
  template <typename T>
  bool operator()(const T* pose, T* residuals) const {
    residuals[0] = translation_weight * (pose[0] - start.x());
    residuals[1] = translation_weight * (pose[1] - start.y());
    residuals[2] = rotation_weight * (pose[2] - start.theta());
    return true;
  }
  Pose2 start;
  double translation_weight;
  double rotation_weight;
};

}  // namespace

Pose2 RefinePoseOnGrid(const OccupancyGrid& grid, const std::vector<Eigen::Vector2d>& points,
                       const Pose2& start, const GridRefinementParams& params) {
  if (!(params.occupied_space_weight >= 0.0 && params.translation_weight >= 0.0 &&
        params.rotation_weight >= 0.0 && params.unknown_probability >= 0.0 &&
        params.unknown_probability <= 1.0 && params.max_iterations >= 0)) {
    throw std::invalid_argument(
        "grid refinement: weights and max_iterations must be >= 0, unknown_probability in [0, 1]");
  }
  if (points.empty()) return start;
  const CorrespondenceCostGrid cells(grid, params.unknown_probability);
  const ceres::BiCubicInterpolator<CorrespondenceCostGrid> map(cells);
  std::array<double, 3> pose{start.x(), start.y(), start.theta()};
  ceres::Problem::Options options;
  options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(options);
  const double weight = params.occupied_space_weight / std::sqrt(double(points.size()));
  problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<OccupiedSpaceCost, ceres::DYNAMIC, 3>(
          new OccupiedSpaceCost(map, points, weight, 1.0 / grid.resolution()),
          static_cast<int>(points.size())),
      nullptr, pose.data());
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<StayNearStartCost, 3, 3>(
                               new StayNearStartCost{start, params.translation_weight,
                                                     params.rotation_weight}),
                           nullptr, pose.data());
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = params.max_iterations;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  return {pose[0], pose[1], pose[2]};
}

}  // namespace slamkit
