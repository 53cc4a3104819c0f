#include <cstdint>
#include <memory>

#include <gtest/gtest.h>

#include "circle_drive.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"

namespace slamkit {
namespace {

using testing::Delayed;
using testing::Drive;
using testing::LandmarksMapped;
using testing::MakeDrive;

// Twenty particles that draw whenever they match a landmark of their tree close the loop as the
// EKF does, tree for tree, on every drive of eight (landmarks drawn from a window are filed and
// found again); FastSLAM 2.0 with as many particles duplicates more trees.
TEST(FastSlamDelayedSampling, ClosesTheLoopAsTheEkfDoes) {
  int standard_excess = 0, delayed_excess = 0;
  for (std::uint64_t seed = 3; seed < 11; ++seed) {
    const Drive d = MakeDrive(90, seed);
    EkfSlam ekf(EkfSlamParams{}, std::make_unique<OdometryModel>(),
                std::make_unique<RangeBearingModel>());
    FastSlam delayed(Delayed(20), std::make_unique<OdometryModel>(),
                     std::make_unique<RangeBearingModel>());
    FastSlamParams p = Delayed(20);
    p.delayed_sampling = false;
    FastSlam standard(p, std::make_unique<OdometryModel>(), std::make_unique<RangeBearingModel>());
    const int trees = static_cast<int>(d.trees.size());
    const int by_ekf = LandmarksMapped(ekf, d);
    const int by_delayed = LandmarksMapped(delayed, d);
    EXPECT_EQ(by_delayed, by_ekf) << "drive " << seed;
    delayed_excess += by_delayed - trees;
    standard_excess += LandmarksMapped(standard, d) - trees;
  }
  EXPECT_LT(delayed_excess, standard_excess);
}

}  // namespace
}  // namespace slamkit
