// `import slamkit`: the module's entry point and its exceptions.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "slamkit/core/numerical_error.hpp"
#include "slamkit/io/error.hpp"

namespace slamkit::python {

py::array_t<double> TrajectoryArray(const Trajectory& trajectory) {
  py::array_t<double> out({static_cast<py::ssize_t>(trajectory.size()), py::ssize_t{4}});
  auto rows = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    const StampedPose& p = trajectory[i];
    const auto r = static_cast<py::ssize_t>(i);
    rows(r, 0) = p.t_s;
    rows(r, 1) = p.pose.x();
    rows(r, 2) = p.pose.y();
    rows(r, 3) = p.pose.theta();
  }
  return out;
}

Trajectory TrajectoryFrom(const py::array_t<double, py::array::c_style | py::array::forcecast>& a) {
  if (a.ndim() != 2 || a.shape(1) != 4) {
    throw py::value_error("a trajectory is an (N, 4) array of t, x, y, theta rows");
  }
  const auto rows = a.unchecked<2>();
  Trajectory out;
  out.reserve(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    out.push_back({rows(i, 0), Pose2(rows(i, 1), rows(i, 2), rows(i, 3))});
  }
  return out;
}

py::object FromJson(const nlohmann::json& json) {
  switch (json.type()) {
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, value] : json.items()) out[py::str(key)] = FromJson(value);
      return out;
    }
    case nlohmann::json::value_t::array: {
      py::list out;
      for (const nlohmann::json& value : json) out.append(FromJson(value));
      return out;
    }
    case nlohmann::json::value_t::string: return py::str(json.get<std::string>());
    case nlohmann::json::value_t::boolean: return py::bool_(json.get<bool>());
    case nlohmann::json::value_t::number_integer: return py::int_(json.get<long long>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(json.get<unsigned long long>());
    case nlohmann::json::value_t::number_float: return py::float_(json.get<double>());
    default: return py::none();
  }
}

}  // namespace slamkit::python

PYBIND11_MODULE(slamkit, m) {
  namespace py = pybind11;
  m.doc() = "slamkit: 2D SLAM on simulated worlds and real robot logs (C++ library bindings)";
  // The messages are the C++ ones: file, line and field for bad input.
  py::register_exception<slamkit::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<slamkit::NumericalError>(m, "NumericalError", PyExc_ArithmeticError);
  slamkit::python::BindIo(m);
  slamkit::python::BindFilters(m);
  slamkit::python::BindEval(m);
  slamkit::python::BindRuns(m);
}
