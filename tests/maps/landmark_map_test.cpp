#include "slamkit/maps/landmark_map.hpp"

#include <gtest/gtest.h>

namespace slamkit {
namespace {

TEST(LandmarkMap, FindsLandmarkBySourceId) {
  LandmarkMap map;
  map.landmarks.push_back({7, {1.0, 2.0}, Eigen::Matrix2d::Identity()});
  map.landmarks.push_back({3, {4.0, 5.0}, Eigen::Matrix2d::Identity()});
  ASSERT_TRUE(map.FindBySource(3).has_value());
  EXPECT_EQ(*map.FindBySource(3), 1);
  EXPECT_EQ(*map.FindBySource(7), 0);
  EXPECT_FALSE(map.FindBySource(kNoLandmark).has_value());
  EXPECT_FALSE(map.FindBySource(4).has_value());
}

}  // namespace
}  // namespace slamkit
