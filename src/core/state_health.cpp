#include "slamkit/core/state_health.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

namespace slamkit {
namespace {

std::string Number(double v) {
  if (std::isnan(v)) return "nan";  // the sign of a NaN means nothing
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

std::string Entry(Eigen::Index i, Eigen::Index j) {
  std::ostringstream s;  // not "(" + std::to_string(i): GCC 12 warns falsely (-Wrestrict) there
  s << '(' << i << ", " << j << ')';
  return s.str();
}

// |P_ij − P_ji| ≤ tolerance for all i < j, scanning column by column (the storage order).
std::optional<std::string> AsymmetryProblem(const Eigen::Ref<const Eigen::MatrixXd>& P,
                                            double tolerance) {
  for (Eigen::Index j = 0; j < P.cols(); ++j) {
    for (Eigen::Index i = 0; i < j; ++i) {
      if (std::abs(P(i, j) - P(j, i)) <= tolerance) continue;
      return "covariance is not symmetric: " + Entry(i, j) + " = " + Number(P(i, j)) + " but " +
             Entry(j, i) + " = " + Number(P(j, i)) + " (tolerance " + Number(tolerance) + ")";
    }
  }
  return std::nullopt;
}

// The smallest eigenvalue ≥ −allowed. A Cholesky factorisation of P + allowed · I succeeds exactly
// when it holds (up to rounding far below `allowed`); the eigenvalues, 20-odd times dearer, are
// computed only when it fails, for the message and to decide a borderline case.
std::optional<std::string> IndefinitenessProblem(const Eigen::Ref<const Eigen::MatrixXd>& P,
                                                 double allowed) {
  if (P.rows() == 0) return std::nullopt;
  Eigen::MatrixXd shifted = P;
  shifted.diagonal().array() += allowed;
  if (allowed > 0.0 && Eigen::LLT<Eigen::MatrixXd>(shifted).info() == Eigen::Success) {
    return std::nullopt;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(P, Eigen::EigenvaluesOnly);
  const double smallest = eigen.eigenvalues().minCoeff();
  if (eigen.info() == Eigen::Success && smallest >= -allowed) return std::nullopt;
  return "covariance is not positive semi-definite: Cholesky of P + " + Number(allowed) +
         " I failed, smallest eigenvalue " + Number(smallest) + " (allowed >= " +
         Number(-allowed) + ")";
}

}  // namespace

bool StateHealthParams::PsdDue(long update, int state_size) const {
  const long interval = std::max(1L, static_cast<long>(psd_interval_per_entry * state_size));
  return update % interval == 0;
}

std::optional<std::string> NonFiniteProblem(const Eigen::Ref<const Eigen::MatrixXd>& m,
                                            std::string_view what) {
  if (m.allFinite()) return std::nullopt;  // the common case, vectorised
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      if (std::isfinite(m(i, j))) continue;
      const std::string at = m.cols() == 1 ? std::to_string(i) : Entry(i, j);
      return std::string(what) + " entry " + at + " is " + Number(m(i, j));
    }
  }
  return std::nullopt;
}

void CheckFinite(const Eigen::Ref<const Eigen::MatrixXd>& m, std::string_view what,
                 std::string_view where) {
  if (auto problem = NonFiniteProblem(m, what)) ThrowNumericalError(where, *problem);
}

std::optional<std::string> GaussianHealthProblem(
    const Eigen::Ref<const Eigen::VectorXd>& mean,
    const Eigen::Ref<const Eigen::MatrixXd>& covariance, const StateHealthParams& params,
    bool check_psd) {
  if (covariance.rows() != covariance.cols() || covariance.rows() != mean.size()) {
    return "covariance is " + std::to_string(covariance.rows()) + " x " +
           std::to_string(covariance.cols()) + " for a mean of " + std::to_string(mean.size());
  }
  if (auto problem = NonFiniteProblem(mean, "mean")) return problem;
  if (auto problem = NonFiniteProblem(covariance, "covariance")) return problem;
  const double scale = covariance.rows() > 0 ? covariance.diagonal().cwiseAbs().maxCoeff() : 0.0;
  if (auto problem = AsymmetryProblem(covariance, params.symmetry_tolerance * scale)) {
    return problem;
  }
  if (check_psd) return IndefinitenessProblem(covariance, params.psd_tolerance * scale);
  return std::nullopt;
}

void CheckGaussianHealth(const Eigen::Ref<const Eigen::VectorXd>& mean,
                         const Eigen::Ref<const Eigen::MatrixXd>& covariance,
                         const StateHealthParams& params, bool check_psd, std::string_view where) {
  if (auto problem = GaussianHealthProblem(mean, covariance, params, check_psd)) {
    ThrowNumericalError(where, *problem);
  }
}

void ThrowNumericalError(std::string_view where, std::string_view problem) {
  throw NumericalError(std::string(where) + ": " + std::string(problem));
}

}  // namespace slamkit
