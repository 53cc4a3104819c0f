#pragma once

#include <gtest/gtest.h>

#include "slamkit/core/pose2.hpp"

namespace slamkit::testing {

// The two poses hold the same numbers, bit for bit.
inline void ExpectSamePose(const Pose2& actual, const Pose2& expected) {
  EXPECT_EQ(actual.vector(), expected.vector());
}

}  // namespace slamkit::testing
