#include "slamkit/io/run_errors_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "common/input_error.hpp"
#include "common/temp_dir.hpp"

namespace slamkit {
namespace {

constexpr const char* kHeader = "t_s,error_x_m,error_y_m,error_theta_rad,nees\n";

class RunErrors : public testing::TempDirTest {
 protected:
  std::string ErrorOf(const std::string& text) const {
    return testing::InputErrorOf([&] { ReadRunErrorsCsv(WriteFile("errors.csv", text)); });
  }
};

// What WriteErrorsCsv writes comes back to the bit, an infinite NEES included.
TEST_F(RunErrors, ReadsRoundTripNumbersAndAnInfiniteNees) {
  const RunErrorsCsv csv = ReadRunErrorsCsv(WriteFile(
      "errors.csv", std::string(kHeader) + "0.025000,-0.001294794483904127,0.1,-3e-05,"
                                           "2.0496833642210461\n0.050000,0,0,0,inf\n"));
  ASSERT_EQ(csv.nees.size(), 2u);
  EXPECT_EQ(csv.t_s[0], 0.025);
  EXPECT_EQ(csv.errors[0].x(), -0.001294794483904127);
  EXPECT_EQ(csv.errors[0].z(), -3e-05);
  EXPECT_EQ(csv.nees[0], 2.0496833642210461);
  EXPECT_TRUE(std::isinf(csv.nees[1]));
}

TEST_F(RunErrors, NamesTheFileLineAndField) {
  EXPECT_NE(ErrorOf("t,x\n").find("errors.csv:1: expected the header"), std::string::npos);
  EXPECT_NE(ErrorOf(std::string(kHeader) + "0.1,0,0,0\n").find("errors.csv:2: expected 5"),
            std::string::npos);
  EXPECT_NE(ErrorOf(std::string(kHeader) + "0.1,0,0,0,1,2\n").find("expected 5"),
            std::string::npos);
  EXPECT_NE(ErrorOf(std::string(kHeader) + "0.1,0,x,0,1\n").find("field 'error_y_m': not a number"),
            std::string::npos);
  EXPECT_NE(ErrorOf(std::string(kHeader) + "0.1,0,0,inf,1\n")
                .find("field 'error_theta_rad': not a finite number"),
            std::string::npos);
  EXPECT_NE(ErrorOf(std::string(kHeader) + "0.1,0,0,0,nan\n").find("field 'nees'"),
            std::string::npos);
  EXPECT_NE(ErrorOf(std::string(kHeader) + "0.1,0,0,0,-1\n").find("a negative NEES"),
            std::string::npos);
}

}  // namespace
}  // namespace slamkit
