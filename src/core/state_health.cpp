#include "slamkit/core/state_health.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace slamkit {
namespace {

[[noreturn]] void Fail(std::string_view where, const std::string& problem) {
  throw NumericalError(std::string(where) + ": " + problem);
}

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
void CheckSymmetric(const Eigen::Ref<const Eigen::MatrixXd>& P, double tolerance,
                    std::string_view where) {
  for (Eigen::Index j = 0; j < P.cols(); ++j) {
    for (Eigen::Index i = 0; i < j; ++i) {
      if (std::abs(P(i, j) - P(j, i)) <= tolerance) continue;
      Fail(where, "covariance is not symmetric: " + Entry(i, j) + " = " + Number(P(i, j)) +
                      " but " + Entry(j, i) + " = " + Number(P(j, i)) + " (tolerance " +
                      Number(tolerance) + ")");
    }
  }
}

// The smallest eigenvalue ≥ −allowed. A Cholesky factorisation of P + allowed · I succeeds exactly
// when it holds (up to rounding far below `allowed`); the eigenvalues, 20-odd times dearer, are
// computed only when it fails, for the message and to decide a borderline case.
void CheckPositiveSemiDefinite(const Eigen::Ref<const Eigen::MatrixXd>& P, double allowed,
                               std::string_view where) {
  if (P.rows() == 0) return;
  Eigen::MatrixXd shifted = P;
  shifted.diagonal().array() += allowed;
  if (allowed > 0.0 && Eigen::LLT<Eigen::MatrixXd>(shifted).info() == Eigen::Success) return;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(P, Eigen::EigenvaluesOnly);
  const double smallest = eigen.eigenvalues().minCoeff();
  if (eigen.info() == Eigen::Success && smallest >= -allowed) return;
  Fail(where, "covariance is not positive semi-definite: Cholesky of P + " + Number(allowed) +
                  " I failed, smallest eigenvalue " + Number(smallest) + " (allowed >= " +
                  Number(-allowed) + ")");
}

}  // namespace

bool StateHealthParams::PsdDue(long update, int state_size) const {
  const long interval = std::max(1L, static_cast<long>(psd_interval_per_entry * state_size));
  return update % interval == 0;
}

void CheckFinite(const Eigen::Ref<const Eigen::MatrixXd>& m, std::string_view what,
                 std::string_view where) {
  if (m.allFinite()) return;  // the common case, vectorised
  for (Eigen::Index j = 0; j < m.cols(); ++j) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      if (std::isfinite(m(i, j))) continue;
      const std::string at = m.cols() == 1 ? std::to_string(i) : Entry(i, j);
      Fail(where, std::string(what) + " entry " + at + " is " + Number(m(i, j)));
    }
  }
}

void CheckGaussianHealth(const Eigen::Ref<const Eigen::VectorXd>& mean,
                         const Eigen::Ref<const Eigen::MatrixXd>& covariance,
                         const StateHealthParams& params, bool check_psd, std::string_view where) {
  if (covariance.rows() != covariance.cols() || covariance.rows() != mean.size()) {
    Fail(where, "covariance is " + std::to_string(covariance.rows()) + " x " +
                    std::to_string(covariance.cols()) + " for a mean of " +
                    std::to_string(mean.size()));
  }
  CheckFinite(mean, "mean", where);
  CheckFinite(covariance, "covariance", where);
  const double scale = covariance.rows() > 0 ? covariance.diagonal().cwiseAbs().maxCoeff() : 0.0;
  CheckSymmetric(covariance, params.symmetry_tolerance * scale, where);
  if (check_psd) CheckPositiveSemiDefinite(covariance, params.psd_tolerance * scale, where);
}

}  // namespace slamkit
