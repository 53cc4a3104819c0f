// The Python module's parts (module.cpp calls each), and the conversions they share.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

#include "slamkit/core/trajectory.hpp"

namespace slamkit::python {

namespace py = pybind11;

void BindIo(py::module_& m);
void BindFilters(py::module_& m);
void BindEval(py::module_& m);
void BindRuns(py::module_& m);

// A trajectory as an (N, 4) array of t, x, y, θ rows (a copy).
py::array_t<double> TrajectoryArray(const Trajectory& trajectory);
// An (N, 4) array of t, x, y, θ rows as a trajectory; ValueError for another shape.
Trajectory TrajectoryFrom(const py::array_t<double, py::array::c_style | py::array::forcecast>& a);
// A JSON value as Python objects (dicts, lists, numbers, strings, None).
py::object FromJson(const nlohmann::json& json);

}  // namespace slamkit::python
