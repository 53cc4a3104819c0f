#include <gtest/gtest.h>

#include <vector>

namespace slamkit {
namespace {

// GCC 12.2 with -O2 -march=native on an AVX-512 machine builds this vector as {0.5, 0.5, 0.5,
// 0.5} (its SLP vectoriser; SLAMKIT_NATIVE_FLAGS in CMakeLists.txt turns it off). Built with the
// project's flags, this test fails where the toolchain would miscompile slamkit.
TEST(Toolchain, BuildsSmallConstantVectorsCorrectly) {
  const std::vector<double> v = {0.5, 0.5, 0.0, 0.0};
  ASSERT_EQ(v.size(), 4u);
  EXPECT_EQ(v[0], 0.5);
  EXPECT_EQ(v[1], 0.5);
  EXPECT_EQ(v[2], 0.0);
  EXPECT_EQ(v[3], 0.0);
}

}  // namespace
}  // namespace slamkit
