#pragma once

#include <cmath>
#include <numbers>

namespace slamkit {

// Maps any angle to [-pi, pi). Uses remainder so it stays exact for large inputs.
inline double WrapAngle(double angle_rad) {
  double a = std::remainder(angle_rad, 2.0 * std::numbers::pi);
  if (a >= std::numbers::pi) a -= 2.0 * std::numbers::pi;
  return a;
}

constexpr double DegToRad(double deg) { return deg * std::numbers::pi / 180.0; }
constexpr double RadToDeg(double rad) { return rad * 180.0 / std::numbers::pi; }

}  // namespace slamkit
