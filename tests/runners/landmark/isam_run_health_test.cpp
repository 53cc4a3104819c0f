// Issue 8 item 7: an iSAM ODOMETRY or LANDMARK of 1e308 used to give exit 0 and a map.csv of
// NaN. The reader now refuses such magnitudes; here the log is built in memory, past the reader,
// and the run must fail with a NumericalError naming the check instead of returning NaN.
#include "slamkit/runners/landmark/isam_run.hpp"

#include <gtest/gtest.h>

#include <string>

#include "slamkit/core/numerical_error.hpp"

namespace slamkit {
namespace {

PointObservation Sighting(double x, double y, LandmarkId id) {
  PointObservation obs;
  obs.z << x, y;
  obs.R = 0.01 * Eigen::Matrix2d::Identity();
  obs.id = id;
  return obs;
}

IsamLog SmallLog(const Eigen::Vector3d& second_odometry, const PointObservation& second_sighting) {
  IsamLog log;
  log.initial_sightings = {Sighting(2.0, 1.0, 0)};
  for (int i = 0; i < 4; ++i) {
    IsamStep step;
    step.pose_index = i + 1;
    step.odometry = i == 1 ? second_odometry : Eigen::Vector3d(1.0, 0.0, 0.1);
    step.odometry_covariance = Eigen::Vector3d(1e-3, 1e-3, 1e-4).asDiagonal();
    step.sightings = {i == 1 ? second_sighting : Sighting(1.0, 1.0, 0)};
    log.steps.push_back(step);
  }
  return log;
}

std::string FailureOf(const IsamLog& log) {
  IsamRunParams params;
  params.ekf.association_method = AssociationMethod::kKnown;
  try {
    RunEkfSlamOnIsam(log, params);
  } catch (const NumericalError& e) {
    return e.what();
  }
  return "";
}

TEST(IsamRunHealth, HealthyLogRuns) {
  EXPECT_EQ(FailureOf(SmallLog(Eigen::Vector3d(1.0, 0.0, 0.1), Sighting(1.0, 2.0, 1))), "");
}

TEST(IsamRunHealth, OverflowingOdometryFailsNamingTheCheck) {
  const std::string failure =
      FailureOf(SmallLog(Eigen::Vector3d(1e308, 0.0, 0.0), Sighting(1.0, 2.0, 1)));
  EXPECT_EQ(failure.rfind("EkfSlam ", 0), 0u) << failure;
  EXPECT_TRUE(failure.find(" is inf") != std::string::npos ||
              failure.find(" is nan") != std::string::npos)
      << failure;
}

TEST(IsamRunHealth, OverflowingLandmarkFailsNamingTheCheck) {
  const std::string failure =
      FailureOf(SmallLog(Eigen::Vector3d(1.0, 0.0, 0.1), Sighting(1e308, 0.0, 1)));
  EXPECT_EQ(failure.rfind("EkfSlam ", 0), 0u) << failure;
  EXPECT_TRUE(failure.find(" is inf") != std::string::npos ||
              failure.find(" is nan") != std::string::npos)
      << failure;
}

}  // namespace
}  // namespace slamkit
