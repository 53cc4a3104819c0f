#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Eigenvalues>

#include "slamkit/filters/grid/gaussian_proposal.hpp"
#include "slamkit/sim/laser_sim.hpp"

namespace slamkit {
namespace {

// A straight corridor along x, mapped over its whole length: scans pin the sideways position
// and the heading, while nothing within the usable range tells where along the corridor they are.
class CorridorProposalTest : public ::testing::Test {
 protected:
  CorridorProposalTest() {
    laser_.sigma_range_m = 0.0;
    ScanInsertionParams insertion;
    insertion.usable_range_m = 8.0;
    for (double x = 0.0; x <= 12.0; x += 1.0) {
      InsertScan(map_, Pose2(x, 0.0, 0.0), ScanAt(Pose2(x, 0.0, 0.0)), insertion);
    }
    weak_prior_ = {.srr = 1.0, .srt = 1.0, .str = 1.0, .stt = 1.0};
  }
  LaserScan ScanAt(const Pose2& pose) {
    Rng rng(1);
    return SimulateScan(corridor_, pose, laser_, rng);
  }
  ProposalDistribution ProposalAt(const Pose2& match) {
    const ScanPoints points = PrepareScan(ScanAt(truth_), 8.0, matcher_);
    return GaussianProposal(map_, points, match, previous_, previous_.Between(truth_), weak_prior_,
                            matcher_);
  }

  const FloorPlan corridor_{{{{-2.0, -1.025}, {40.0, -1.025}}, {{-2.0, 1.025}, {40.0, 1.025}}}};
  LaserSimParams laser_;
  OccupancyGrid map_;
  ScanMatcherParams matcher_;
  OdometryNoiseParams weak_prior_;
  const Pose2 truth_{5.0, 0.0, 0.0};
  const Pose2 previous_{4.0, 0.0, 0.0};
};

TEST_F(CorridorProposalTest, CovarianceIsWideAlongTheCorridorAndNarrowAcross) {
  const ProposalDistribution proposal = ProposalAt(truth_);
  const Eigen::Matrix3d& c = proposal.covariance;
  EXPECT_TRUE(c.isApprox(c.transpose()));
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(c).eigenvalues().minCoeff(), -1e-15);
  EXPECT_GT(c(0, 0), 4.0 * c(1, 1)) << "along " << c(0, 0) << ", across " << c(1, 1);
  EXPECT_NEAR(proposal.mean.y(), truth_.y(), 0.005);
  EXPECT_NEAR(proposal.mean.theta(), truth_.theta(), 0.005);
}

TEST_F(CorridorProposalTest, NormaliserFavoursAMatchThatFits) {
  const double fits = ProposalAt(truth_).log_normaliser;
  const double off = ProposalAt(truth_.Compose(Pose2(0.0, 0.1, 0.0))).log_normaliser;
  EXPECT_GT(fits, off + 10.0);
}

TEST_F(CorridorProposalTest, DrawsFollowTheFittedGaussian) {
  const ProposalDistribution proposal = ProposalAt(truth_);
  Rng rng(9);
  const int n = 20000;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n; ++i) {
    const Pose2 x = SampleProposal(proposal, rng);
    const Eigen::Vector3d d(x.x() - proposal.mean.x(), x.y() - proposal.mean.y(),
                            x.theta() - proposal.mean.theta());
    sum += d;
    sum_sq += d * d.transpose();
  }
  const Eigen::Matrix3d sample_cov = sum_sq / n - (sum / n) * (sum / n).transpose();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(sample_cov(k, k) / proposal.covariance(k, k), 1.0, 0.05) << k;
  }
}

// Where the match leaves the corridor's axis unconstrained, the proposal neither moves its mean
// along the axis nor spreads along it (the motion sample already carries that spread); across
// it and in heading it is the fitted Gaussian unchanged.
TEST_F(CorridorProposalTest, KeepsOnlyTheConstrainedPartWhereTheMatchSaysSo) {
  const Pose2 match(5.0, 0.0, 0.3);  // the robot's x at 0.3 rad in the world
  ProposalDistribution proposal = ProposalAt(match);
  const ProposalDistribution fitted = proposal;
  MatchConstraints c;
  c.keep = Eigen::Vector3d(0.0, 1.0, 1.0).asDiagonal();
  c.unconstrained = 1;
  KeepConstrainedPart(c, match, &proposal);
  const Eigen::Vector3d along(std::cos(0.3), std::sin(0.3), 0.0);
  const Eigen::Vector3d across(-std::sin(0.3), std::cos(0.3), 0.0);
  const Eigen::Vector3d moved(proposal.mean.x() - match.x(), proposal.mean.y() - match.y(),
                              proposal.mean.theta() - match.theta());
  const Eigen::Vector3d fitted_moved(fitted.mean.x() - match.x(), fitted.mean.y() - match.y(),
                                     fitted.mean.theta() - match.theta());
  EXPECT_NEAR(along.dot(moved), 0.0, 1e-12);
  EXPECT_NEAR(across.dot(moved), across.dot(fitted_moved), 1e-12);
  EXPECT_NEAR(moved.z(), fitted_moved.z(), 1e-12);
  EXPECT_NEAR(along.dot(proposal.covariance * along), 0.0, 1e-15);
  EXPECT_GT(along.dot(fitted.covariance * along), 1e-6) << "nothing to remove: the test is moot";
  EXPECT_NEAR(across.dot(proposal.covariance * across), across.dot(fitted.covariance * across),
              1e-15);
  EXPECT_NEAR(proposal.covariance(2, 2), fitted.covariance(2, 2), 1e-15);
  EXPECT_EQ(proposal.log_normaliser, fitted.log_normaliser);
}

}  // namespace
}  // namespace slamkit
