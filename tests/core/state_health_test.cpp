#include "slamkit/core/state_health.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Dense>

#include "slamkit/core/rng.hpp"

namespace slamkit {
namespace {

// What CheckGaussianHealth() threw ("" if nothing): the tests check that it names the check.
std::string Failure(const Eigen::VectorXd& mean, const Eigen::MatrixXd& P, bool check_psd = true,
                    const StateHealthParams& params = {}) {
  try {
    CheckGaussianHealth(mean, P, params, check_psd, "step 7");
  } catch (const NumericalError& e) {
    return e.what();
  }
  return "";
}

// A random covariance of rank `rank` (positive definite when rank = n).
Eigen::MatrixXd RandomCovariance(int n, int rank, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd A(n, rank);
  for (int j = 0; j < rank; ++j) {
    for (int i = 0; i < n; ++i) A(i, j) = rng.Normal(0.0, 1.0);
  }
  return A * A.transpose();
}

TEST(StateHealth, HealthyStatesPass) {
  EXPECT_EQ(Failure(Eigen::VectorXd::Zero(6), RandomCovariance(6, 6, 1)), "");
  // Semi-definite: a state with directions of zero variance (a pose known exactly).
  EXPECT_EQ(Failure(Eigen::VectorXd::Zero(40), RandomCovariance(40, 7, 2)), "");
  EXPECT_EQ(Failure(Eigen::VectorXd::Zero(3), Eigen::MatrixXd::Zero(3, 3)), "");
  EXPECT_EQ(Failure(Eigen::VectorXd(), Eigen::MatrixXd()), "");
}

TEST(StateHealth, RoundingBelowTheTolerancesPasses) {
  Eigen::MatrixXd P = RandomCovariance(30, 10, 3);
  const double scale = P.diagonal().maxCoeff();
  P(4, 9) += 1e-13 * scale;  // asymmetric by rounding
  P.diagonal().array() -= 1e-12 * scale;  // eigenvalues of the null space just below zero
  EXPECT_EQ(Failure(Eigen::VectorXd::Zero(30), P), "");
}

TEST(StateHealth, NonFiniteMeanIsNamed) {
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(5);
  mean[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(Failure(mean, RandomCovariance(5, 5, 4)), "step 7: mean entry 2 is nan");
}

TEST(StateHealth, NonFiniteCovarianceEntryIsNamed) {
  Eigen::MatrixXd P = RandomCovariance(5, 5, 5);
  P(3, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(Failure(Eigen::VectorXd::Zero(5), P), "step 7: covariance entry (3, 1) is nan");
  P(3, 1) = P(1, 3);
  P(0, 4) = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(Failure(Eigen::VectorXd::Zero(5), P), "step 7: covariance entry (0, 4) is -inf");
}

TEST(StateHealth, AsymmetryIsNamed) {
  Eigen::MatrixXd P = RandomCovariance(5, 5, 6);
  P(1, 3) += 1e-3 * P.diagonal().maxCoeff();
  const std::string failure = Failure(Eigen::VectorXd::Zero(5), P);
  EXPECT_EQ(failure.rfind("step 7: covariance is not symmetric: (1, 3) = ", 0), 0u) << failure;
}

TEST(StateHealth, NegativeEigenvalueIsNamed) {
  // A rotation of diag(4, 1, -0.5): symmetric, finite, indefinite.
  const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Eigen::Matrix3d P = Q * Eigen::Vector3d(4, 1, -0.5).asDiagonal() * Q.transpose();
  const std::string failure = Failure(Eigen::VectorXd::Zero(3), P);
  EXPECT_NE(failure.find("step 7: covariance is not positive semi-definite"), std::string::npos)
      << failure;
  EXPECT_NE(failure.find("smallest eigenvalue -0.5"), std::string::npos) << failure;
  EXPECT_EQ(Failure(Eigen::VectorXd::Zero(3), P, /*check_psd=*/false), "");
}

TEST(StateHealth, ZeroVarianceWithCorrelationIsIndefinite) {
  Eigen::Matrix2d P;
  P << 0.0, 0.1, 0.1, 1.0;  // P_00 = 0 but correlated: eigenvalues of both signs
  EXPECT_NE(Failure(Eigen::VectorXd::Zero(2), P).find("not positive semi-definite"),
            std::string::npos);
}

TEST(StateHealth, MismatchedSizesAreNamed) {
  EXPECT_EQ(Failure(Eigen::VectorXd::Zero(2), Eigen::MatrixXd::Identity(3, 3)),
            "step 7: covariance is 3 x 3 for a mean of 2");
}

TEST(StateHealth, CheckFiniteNamesTheEntry) {
  Eigen::Vector3d pose(1.0, std::numeric_limits<double>::infinity(), 0.0);
  try {
    CheckFinite(pose, "particle 4's pose", "scan 9");
    FAIL() << "no throw";
  } catch (const NumericalError& e) {
    EXPECT_STREQ(e.what(), "scan 9: particle 4's pose entry 1 is inf");
  }
  EXPECT_NO_THROW(CheckFinite(Eigen::Vector3d(1, 2, 3), "pose", "here"));
}

TEST(StateHealth, PsdScheduleKeepsItsCostPerUpdateQuadratic) {
  const StateHealthParams params;
  for (long k = 1; k <= 5; ++k) EXPECT_TRUE(params.PsdDue(k, 3));  // the pose alone
  int due = 0;
  for (long k = 1; k <= 310; ++k) due += params.PsdDue(k, 63) ? 1 : 0;  // 30 landmarks
  EXPECT_EQ(due, 10);  // every 31st
  StateHealthParams always = params;
  always.psd_interval_per_entry = 0.0;
  EXPECT_TRUE(always.PsdDue(7, 1003));
}

TEST(StateHealth, DefaultModeFollowsTheBuild) {
#ifdef NDEBUG
  EXPECT_EQ(StateHealthParams{}.mode, StateHealthMode::kAtOutput);
#else
  EXPECT_EQ(StateHealthParams{}.mode, StateHealthMode::kEveryUpdate);
#endif
}

}  // namespace
}  // namespace slamkit
