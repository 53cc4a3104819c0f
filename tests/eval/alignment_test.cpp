#include "slamkit/eval/alignment.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "slamkit/core/rng.hpp"
#include "common/ordered_draws.hpp"

namespace slamkit {
namespace {

TEST(AlignPoints, RecoversKnownRigidMotion) {
  Rng rng(5);
  const Pose2 motion(3.0, -1.5, 0.7);
  std::vector<Eigen::Vector2d> from, to;
  for (int i = 0; i < 30; ++i) {
    from.push_back(testing::UniformVector2(rng, -10, 10, -10, 10));
    to.push_back(motion.TransformFrom(from.back()));
  }
  const RigidAlignment a = AlignPoints(from, to);
  EXPECT_NEAR(a.transform.x(), 3.0, 1e-9);
  EXPECT_NEAR(a.transform.y(), -1.5, 1e-9);
  EXPECT_NEAR(a.transform.theta(), 0.7, 1e-12);
  EXPECT_NEAR(a.rmse_m, 0.0, 1e-9);
}

TEST(AlignPoints, ResidualIsTheNoiseThatNoMotionExplains) {
  // Two points moved apart symmetrically: no rigid motion fixes it, the residual is 0.5 m.
  const std::vector<Eigen::Vector2d> from = {{0, 0}, {2, 0}};
  const std::vector<Eigen::Vector2d> to = {{-0.5, 0}, {2.5, 0}};
  const RigidAlignment a = AlignPoints(from, to);
  EXPECT_NEAR(a.rmse_m, 0.5, 1e-12);
  EXPECT_NEAR(a.transform.theta(), 0.0, 1e-12);
}

}  // namespace
}  // namespace slamkit
