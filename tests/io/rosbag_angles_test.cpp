// A LaserScan's float32 angles taken back to the doubles a driver rounded (LaserScanAngles): the
// multiples of π common lasers use come back exactly, anything else stays as the message had it.
#include <gtest/gtest.h>

#include <cmath>

#include "slamkit/io/rosbag_reader.hpp"

namespace slamkit {
namespace {

std::pair<double, double> FromFloat32(double angle_min, double increment) {
  return LaserScanAngles(static_cast<float>(angle_min), static_cast<float>(increment));
}

TEST(LaserScanAngles, CommonLasersComeBackAsTheirMultiplesOfPi) {
  // A SICK LMS at 1° over 180° (the CARMEN logs' FLASER scans: −π/2 + i·π/180 in double).
  EXPECT_EQ(FromFloat32(-M_PI / 2, M_PI / 180), std::make_pair(-M_PI / 2, M_PI / 180));
  // Hokuyo UTM-30LX: −135° in steps of 0.25°.
  EXPECT_EQ(FromFloat32(-3 * M_PI / 4, M_PI / 720), std::make_pair(-3 * M_PI / 4, M_PI / 720));
  // Half an increment off the axis (beams centred on their sectors).
  EXPECT_EQ(FromFloat32(M_PI * -179.0 / 360.0, M_PI / 180).first, M_PI * -179.0 / 360.0);
}

TEST(LaserScanAngles, OtherValuesStayAsTheMessageHadThem) {
  // Hokuyo URG-04LX: 360°/1024 is π/512, its start −2.0862 rad is no multiple of π/1024.
  const float urg_min = -2.0862f;
  const auto urg = LaserScanAngles(urg_min, static_cast<float>(M_PI / 512));
  EXPECT_EQ(urg.first, static_cast<double>(urg_min));
  EXPECT_EQ(urg.second, M_PI / 512);
  // An increment that is no π/N: both kept, even an angle_min that is a multiple of π.
  const float odd = 0.0123f, half_pi = static_cast<float>(-M_PI / 2);
  EXPECT_EQ(LaserScanAngles(half_pi, odd),
            std::make_pair(static_cast<double>(half_pi), static_cast<double>(odd)));
  // One float32 step away from π/180 is another increment, not a rounded π/180.
  const float near = std::nextafter(static_cast<float>(M_PI / 180), 1.0f);
  EXPECT_EQ(LaserScanAngles(half_pi, near).second, static_cast<double>(near));
  // Zero, negative and non-finite increments are left to the reader's checks.
  for (const float bad : {0.0f, -0.01f, std::nanf("")}) {
    EXPECT_EQ(LaserScanAngles(half_pi, bad).first, static_cast<double>(half_pi));
  }
}

}  // namespace
}  // namespace slamkit
