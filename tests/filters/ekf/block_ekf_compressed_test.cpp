// Compressed updates (Guivant & Nebot 2001) against the uncompressed BlockEkf driven through the
// same predictions, sightings and new landmarks: equal after every global update, and every read
// equal while an area is open.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <vector>

#include "common/landmark_inputs.hpp"
#include "common/ordered_draws.hpp"
#include "filters/compressed_circle.hpp"
#include "slamkit/core/rng.hpp"
#include "slamkit/filters/ekf/block_ekf.hpp"
#include "slamkit/filters/ekf/observation_model.hpp"
#include "slamkit/filters/ekf/point_landmark_model.hpp"
#include "slamkit/filters/features/line_landmark_model.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/range_bearing.hpp"

namespace slamkit {
namespace {

using testing::Odo;

using testing::RelativeDiff;

// A world of point landmarks on a jittered grid, a robot driving a loop through it, and two
// filters given the same steps: `dense` as it always ran, `compressed` with areas.
class CompressedRun {
 public:
  CompressedRun() : dense_(16), compressed_(16) {
    Rng rng(5);
    for (double x = -20.0; x <= 20.0; x += 4.0) {
      for (double y = -20.0; y <= 20.0; y += 4.0) {
        world_.push_back(Eigen::Vector2d(x, y) + testing::UniformVector2(rng, -1, 1, -1, 1));
      }
    }
    block_of_.assign(world_.size(), -1);
    for (BlockEkf* f : {&dense_, &compressed_}) {
      point_kind_ = f->RegisterKind({2, {}, false});
      f->AddBlock(kPoseKind, Eigen::Vector3d(0.0, -15.0, 0.0),
                  Eigen::Vector3d(1e-4, 1e-4, 1e-5).asDiagonal());
    }
  }

  // One step: odometry along a circle of radius 15 m, then every landmark within 8 m sighted
  // (new ones added) on both filters.
  void Step(Rng& rng) {
    const Control u = Odo(0.4, 0.0, 0.4 / 15.0);
    truth_ = motion_.Move(truth_, u, 0.1);
    const Control noisy = Odo(0.4 + rng.Normal(0, 0.02), rng.Normal(0, 0.01),
                              0.4 / 15.0 + rng.Normal(0, 0.005));
    for (BlockEkf* f : {&dense_, &compressed_}) {
      Eigen::Matrix3d F;
      ControlJacobian G;
      const Pose2 moved = motion_.Move(f->PoseOf(0), noisy, 0.1, &F, &G);
      f->PredictPose(0, moved, F, G, motion_.Noise(noisy, 0.1));
    }
    for (std::size_t l = 0; l < world_.size(); ++l) {
      const RangeBearing rb = PredictRangeBearing(truth_, world_[l]);
      if (rb.range_m > 8.0) continue;
      const Eigen::Vector2d z(rb.range_m + rng.Normal(0, 0.05), rb.bearing_rad + rng.Normal(0, 0.01));
      Sight(static_cast<int>(l), z);
    }
    dense_.ApplyPendingDowndate();
    compressed_.ApplyPendingDowndate();
  }

  // An area of the pose and the landmarks within `radius_m` of it.
  void Recompress(double radius_m) {
    std::vector<int> active = {0};
    for (const int b : block_of_) {
      if (b >= 0 && (compressed_.Mean(b) - compressed_.PoseOf(0).translation()).norm() < radius_m) {
        active.push_back(b);
      }
    }
    compressed_.Compress(active);
  }

  void ExpectEqual(const std::string& where) const {
    ASSERT_EQ(compressed_.StateSize(), dense_.StateSize()) << where;
    EXPECT_LT(RelativeDiff(compressed_.State(), dense_.State()), 1e-9) << where;
    EXPECT_LT(RelativeDiff(compressed_.Covariance(), dense_.Covariance()), 1e-9) << where;
  }

  BlockEkf& dense() { return dense_; }
  BlockEkf& compressed() { return compressed_; }
  const std::vector<int>& blocks() const { return block_of_; }

 private:
  void Sight(int landmark, const Eigen::Vector2d& z) {
    const Eigen::Matrix2d R = Eigen::Vector2d(0.05 * 0.05, 0.01 * 0.01).asDiagonal();
    const PointLandmarkModel model(sensor_, point_kind_, 5.0);
    if (block_of_[landmark] < 0) {
      const int observers[] = {0};
      block_of_[landmark] = AugmentFrom(model, dense_, observers, z, R);
      EXPECT_EQ(AugmentFrom(model, compressed_, observers, z, R), block_of_[landmark]);
      return;
    }
    const int blocks[] = {0, block_of_[landmark]};
    ASSERT_TRUE(dense_.Update(Linearise(model, dense_, blocks, z, R)));
    ASSERT_TRUE(compressed_.Update(Linearise(model, compressed_, blocks, z, R)));
  }

  const RangeBearingModel sensor_;
  const OdometryModel motion_;
  std::vector<Eigen::Vector2d> world_;
  std::vector<int> block_of_;  // per world landmark: its block, or −1 before it is seen
  Pose2 truth_{0.0, -15.0, 0.0};
  BlockEkf dense_, compressed_;
  int point_kind_ = -1;
};

TEST(CompressedEkf, EqualsTheDenseFilterAfterEveryGlobalUpdate) {
  CompressedRun run;
  Rng rng(6);
  int synchronisations = 0;
  // 1.3 laps (300 steps of 0.4 m on a 94 m circle): landmarks are added inside areas, and old
  // ones re-enter areas after a lap.
  for (int step = 0; step < 300; ++step) {
    if (step % 25 == 0) {
      run.compressed().Synchronise();
      ++synchronisations;
      run.ExpectEqual("after the global update at step " + std::to_string(step));
      if (::testing::Test::HasFailure()) return;
      run.Recompress(12.0);
      if (step >= 100) {
        EXPECT_LT(run.compressed().ActiveSize(), run.compressed().StateSize());
      }
    }
    run.Step(rng);
  }
  run.compressed().Synchronise();
  run.ExpectEqual("at the end");
  EXPECT_GT(run.dense().StateSize(), 150);
  EXPECT_EQ(synchronisations, 12);
}

TEST(CompressedEkf, ReadsWhileAnAreaIsOpenAreTheDenseFiltersReads) {
  CompressedRun run;
  Rng rng(7);
  for (int step = 0; step < 120; ++step) run.Step(rng);
  run.Recompress(13.0);  // the sensor's 8 m and the 4 m driven below
  for (int step = 0; step < 10; ++step) run.Step(rng);
  const BlockEkf& c = run.compressed();
  ASSERT_TRUE(c.IsCompressed());
  int inactive = 0;
  for (const int b : run.blocks()) {
    if (b < 0) continue;
    inactive += c.IsActive(b) ? 0 : 1;
    EXPECT_LT(RelativeDiff(c.Mean(b), run.dense().Mean(b)), 1e-9) << "block " << b;
    EXPECT_LT(RelativeDiff(c.CovarianceBlock(b, b), run.dense().CovarianceBlock(b, b)), 1e-9);
    EXPECT_LT(RelativeDiff(c.CovarianceBlock(0, b), run.dense().CovarianceBlock(0, b)), 1e-9);
    EXPECT_LT(RelativeDiff(c.CovarianceBlock(b, 1), run.dense().CovarianceBlock(b, 1)), 1e-9);
  }
  EXPECT_GT(inactive, 10);
  // The batched read of the diagonal blocks, inside and outside the area, is the same.
  std::vector<int> mapped;
  for (const int b : run.blocks()) {
    if (b >= 0) mapped.push_back(b);
  }
  const std::vector<Eigen::MatrixXd> diagonal = c.DiagonalBlocks(mapped);
  ASSERT_EQ(diagonal.size(), mapped.size());
  for (std::size_t i = 0; i < mapped.size(); ++i) {
    EXPECT_LT(RelativeDiff(diagonal[i], run.dense().CovarianceBlock(mapped[i], mapped[i])), 1e-9)
        << "block " << mapped[i];
  }
  EXPECT_TRUE(c.IsCompressed());  // reads do not close the area
  run.ExpectEqual("through an open area");
  EXPECT_FALSE(c.HealthProblem({}, true).has_value());
  // A copy carries its area and goes on as the original does.
  BlockEkf copy = c;
  run.compressed().Synchronise();
  copy.Synchronise();
  EXPECT_TRUE(copy.State() == run.compressed().State());
  EXPECT_TRUE(copy.Covariance() == run.compressed().Covariance());
}

TEST(CompressedEkf, AnUpdateReachingOutsideTheAreaSynchronisesFirst) {
  CompressedRun run;
  Rng rng(8);
  for (int step = 0; step < 120; ++step) run.Step(rng);
  run.Recompress(3.0);  // smaller than the sensor's 8 m: sightings reach outside the area
  const int before = run.compressed().ActiveSize();
  ASSERT_GT(before, 0);
  run.Step(rng);
  EXPECT_FALSE(run.compressed().IsCompressed());
  run.ExpectEqual("after a step that left the area");
}

// A line block outside the area whose ρ a correlated update takes below zero: the dense filter
// flips it to (−ρ, α + π) at once (its kind's normalise step), so reads of the outside block must
// show it flipped too, its cross-covariances with their sign changed.
TEST(CompressedEkf, AnOutsideLineReadsAsTheDenseFilterNormalisesIt) {
  BlockEkf dense(16);
  const int point_kind = dense.RegisterKind({2, {}, false});
  const int line_kind = dense.RegisterKind(LineBlockKind());
  dense.AddBlock(kPoseKind, Eigen::Vector3d::Zero(), Eigen::Vector3d(0.01, 0.01, 0.001).asDiagonal());
  const int point = dense.AddBlock(point_kind, Eigen::Vector2d(3.0, 1.0), Eigen::Matrix2d::Identity());
  // ρ follows the point's x one for one: ρ = 0.02 + (x − 3).
  BlockMatrix J_line_point = BlockMatrix::Zero(2, 2);
  J_line_point(0, 0) = 1.0;
  const BlockJacobian from_point{point, J_line_point};
  const int line = dense.Augment(line_kind, Eigen::Vector2d(0.02, 0.5), std::span(&from_point, 1),
                                 BlockMatrix::Identity(2, 2), BlockMatrix::Identity(2, 2) * 1e-4);
  BlockEkf compressed = dense;
  const int active[] = {0, point};
  compressed.Compress(active);
  ASSERT_FALSE(compressed.IsActive(line));
  // The point's x is measured 0.1 m lower than its mean, with a tiny noise.
  Linearisation obs;
  obs.innovation = BlockVector::Constant(1, -0.1);
  obs.H.Add(point, BlockMatrix::Identity(1, 2));
  obs.R = BlockMatrix::Constant(1, 1, 1e-6);
  for (BlockEkf* f : {&dense, &compressed}) {
    ASSERT_TRUE(f->Update(obs));
    f->ApplyPendingDowndate();
  }
  ASSERT_TRUE(compressed.IsCompressed());
  ASSERT_GT(dense.Mean(line)[0], 0.05);  // flipped: ρ ≈ 0.08, not −0.08
  EXPECT_LT(RelativeDiff(compressed.Mean(line), dense.Mean(line)), 1e-9);
  EXPECT_LT(RelativeDiff(compressed.CovarianceBlock(line, line), dense.CovarianceBlock(line, line)),
            1e-9);
  EXPECT_LT(RelativeDiff(compressed.CovarianceBlock(line, point),
                         dense.CovarianceBlock(line, point)), 1e-9);
  EXPECT_LT(RelativeDiff(compressed.CovarianceBlock(point, line),
                         dense.CovarianceBlock(point, line)), 1e-9);
  EXPECT_LT(RelativeDiff(compressed.CovarianceBlock(0, line), dense.CovarianceBlock(0, line)),
            1e-9);
  const int both[] = {line, point};
  const std::vector<Eigen::MatrixXd> diagonal = compressed.DiagonalBlocks(both);
  EXPECT_LT(RelativeDiff(diagonal[0], dense.CovarianceBlock(line, line)), 1e-9);
  EXPECT_LT(RelativeDiff(diagonal[1], dense.CovarianceBlock(point, point)), 1e-9);
  compressed.Synchronise();
  EXPECT_LT(RelativeDiff(compressed.State(), dense.State()), 1e-9);
  EXPECT_LT(RelativeDiff(compressed.Covariance(), dense.Covariance()), 1e-9);
}

}  // namespace
}  // namespace slamkit
