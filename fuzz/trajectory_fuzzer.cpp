// ReadTrajectory (`t x y theta` or TUM `t x y z qx qy qz qw` lines, plain or gzip).

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/trajectory_reader.hpp"

int slamkit::fuzz::FuzzTrajectory(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  try {
    const auto poses = slamkit::ReadTrajectory(WriteFile("poses.txt", AsText(data, size)));
    Check(!poses.empty(), "a trajectory has at least one pose");
    for (const auto& p : poses) {
      Check(std::isfinite(p.t_s) && p.pose.vector().allFinite(), "poses are finite");
      Check(p.pose.translation().cwiseAbs().maxCoeff() <= 1e6, "positions are bounded by 1e6");
    }
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
