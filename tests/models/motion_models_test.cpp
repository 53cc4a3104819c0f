#include <gtest/gtest.h>

#include "common/numeric_jacobian.hpp"
#include "slamkit/models/vehicle.hpp"

namespace slamkit {
namespace {

using testing::NumericJacobian;
using testing::RandomPose;

Control RandomControl(MotionKind kind, Rng& rng) {
  Control u(kind == MotionKind::kOdometry ? 3 : 2);
  u[0] = rng.Uniform(-1.0, 4.0);
  u[1] = rng.Uniform(-0.5, 0.5);
  if (kind == MotionKind::kOdometry) u[2] = rng.Uniform(-0.3, 0.3);
  return u;
}

class MotionModelTest : public ::testing::TestWithParam<MotionKind> {};

TEST_P(MotionModelTest, JacobiansMatchCentralDifferences) {
  VehicleParams params;
  params.kind = GetParam();
  const auto model = MakeMotionModel(params);
  Rng rng(5);
  const double dt = 0.1;
  for (int i = 0; i < 100; ++i) {
    const Pose2 x = RandomPose(rng);
    const Control u = RandomControl(params.kind, rng);
    Eigen::Matrix3d J_x;
    ControlJacobian J_u;
    model->Move(x, u, dt, &J_x, &J_u);
    auto by_x = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return model->Move(Pose2(v), u, dt).vector();
    };
    auto by_u = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
      return model->Move(x, Control(v), dt).vector();
    };
    EXPECT_TRUE(J_x.isApprox(NumericJacobian(by_x, x.vector(), 2), 1e-6));
    const Eigen::MatrixXd J_u_num = NumericJacobian(by_u, Eigen::VectorXd(u), 2);
    EXPECT_TRUE(Eigen::MatrixXd(J_u).isApprox(J_u_num, 1e-6)) << J_u << "\n" << J_u_num;
    EXPECT_EQ(model->Noise(u, dt).rows(), model->ControlDim());
  }
}

INSTANTIATE_TEST_SUITE_P(AllKinds, MotionModelTest,
                         ::testing::Values(MotionKind::kUnicycle, MotionKind::kCarLike,
                                           MotionKind::kOdometry));

TEST(CarLikeModel, FollowsSpecEquationTwo) {
  CarLikeParams p;
  p.wheelbase_m = 2.5;
  const CarLikeModel model(p);
  Control u(2);
  u << 3.0, 0.2;
  const Pose2 x(1.0, 2.0, 0.3);
  const Pose2 y = model.Move(x, u, 0.5);
  EXPECT_NEAR(y.x(), 1.0 + 1.5 * std::cos(0.5), 1e-12);
  EXPECT_NEAR(y.y(), 2.0 + 1.5 * std::sin(0.5), 1e-12);
  EXPECT_NEAR(y.theta(), 0.3 + 1.5 * std::sin(0.2) / 2.5, 1e-12);
}

TEST(UnicycleModel, DrivesAFullCircleBackToStart) {
  const UnicycleModel model;
  Control u(2);
  u << 1.0, 2.0 * M_PI / 100.0;  // one turn in 100 s
  Pose2 x;
  for (int i = 0; i < 1000; ++i) x = model.Move(x, u, 0.1);
  EXPECT_NEAR(x.x(), 0.0, 1e-6);
  EXPECT_NEAR(x.y(), 0.0, 1e-6);
  EXPECT_NEAR(x.theta(), 0.0, 1e-9);
}

}  // namespace
}  // namespace slamkit
