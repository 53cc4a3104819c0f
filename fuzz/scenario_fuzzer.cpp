// LoadScenario (scenario YAML, configs/*.yaml). A small valid landmarks.csv sits next to the
// scenario file, so that `world: {kind: csv, landmarks_csv: landmarks.csv}` reaches the CSV
// reader too (the CSV reader's own harness is landmark_csv_fuzzer.cpp).

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/runners/landmark/scenario_config.hpp"

int slamkit::fuzz::FuzzScenario(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  static const bool csv_written = (WriteFile("landmarks.csv", "id,x_m,y_m\n0,1,2\n1,3,-4\n"), true);
  (void)csv_written;
  try {
    const slamkit::ScenarioConfig config =
        slamkit::LoadScenario(WriteFile("scenario.yaml", AsText(data, size)));
    const slamkit::ScenarioParams& p = config.scenario;
    Check(p.route.waypoints_m.size() >= 2, "a scenario has a route");
    // Every number the file gives is finite (scenario_config.hpp), the `_deg` ones after their
    // conversion to radians too.
    const slamkit::VehicleParams& v = p.vehicle;
    const slamkit::ControllerParams& c = p.controller;
    const slamkit::RangeBearingParams& s = p.sensor;
    Check(p.initial_pose.vector().allFinite(), "the initial pose is finite");
    Check(std::isfinite(v.car_like.sigma_steer_rad) && std::isfinite(v.unicycle.sigma_omega_radps) &&
              std::isfinite(v.odometry.sigma_theta_rad),
          "the vehicle's angles are finite");
    Check(std::isfinite(c.max_steer_rad) && std::isfinite(c.max_steer_rate_radps) &&
              std::isfinite(c.max_turn_rate_radps),
          "the controller's angles are finite");
    Check(std::isfinite(s.fov_rad) && std::isfinite(s.sigma_bearing_rad),
          "the sensor's angles are finite");
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
