#pragma once

#include <filesystem>
#include <vector>

#include <Eigen/Core>

namespace slamkit {

// A Monte Carlo run's errors.csv (`t_s,error_x_m,error_y_m,error_theta_rad,nees`, as
// WriteErrorsCsv writes it, every number at round-trip precision): what `slamkit merge` rebuilds
// a study's aggregates from.
struct RunErrorsCsv {
  std::vector<double> t_s;
  std::vector<Eigen::Vector3d> errors;
  std::vector<double> nees;  // may be +inf (a covariance that rules the error out)
};

// Throws InputError naming the file, the line and the field for a missing or wrong header, a
// line without five fields, a number that does not parse, a non-finite time or error, a NaN or
// negative NEES.
RunErrorsCsv ReadRunErrorsCsv(const std::filesystem::path& path);

}  // namespace slamkit
