// Metrics on trajectories and estimates: ATE, RPE, the relations metric, NEES and its band.
#include <pybind11/eigen.h>

#include "bindings.hpp"
#include "slamkit/eval/consistency.hpp"
#include "slamkit/eval/errors.hpp"
#include "slamkit/eval/trajectory_errors.hpp"

namespace slamkit::python {
namespace {

using Rows = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<PoseRelation> RelationsFrom(const Rows& a) {
  if (a.ndim() != 2 || a.shape(1) != 5) {
    throw py::value_error("relations are an (N, 5) array of t1, t2, dx, dy, dtheta rows");
  }
  std::vector<PoseRelation> out;
  for (py::ssize_t i = 0; i < a.shape(0); ++i) {
    out.push_back({a.at(i, 0), a.at(i, 1), Pose2(a.at(i, 2), a.at(i, 3), a.at(i, 4))});
  }
  return out;
}

py::dict RelationsDict(const RelationErrorStats& s) {
  py::dict d;
  d["count"] = s.count;
  d["skipped"] = s.skipped;
  d["trans_mean_m"] = s.trans_mean_m;
  d["trans_std_m"] = s.trans_std_m;
  d["rot_mean_deg"] = s.rot_mean_deg;
  d["rot_std_deg"] = s.rot_std_deg;
  return d;
}

py::dict AteDict(const AbsoluteTrajectoryErrorStats& s) {
  py::dict d;
  d["count"] = s.count;
  d["rmse_m"] = s.rmse_m;
  d["mean_m"] = s.mean_m;
  d["max_m"] = s.max_m;
  return d;
}

}  // namespace

void BindEval(py::module_& m) {
  m.def(
      "evaluate_relations",
      [](const Rows& estimate, const Rows& relations, double time_tolerance, bool covered_only) {
        const Trajectory trajectory = TrajectoryFrom(estimate);
        std::vector<PoseRelation> r = RelationsFrom(relations);
        if (covered_only) r = RelationsCovered(trajectory, r, time_tolerance);
        return RelationsDict(EvaluateRelations(trajectory, r, time_tolerance));
      },
      py::arg("estimate"), py::arg("relations"), py::arg("time_tolerance") = 1e-3,
      py::arg("covered_only") = false,
      "Kümmerle et al.'s relations metric; covered_only: only the relations whose two times have "
      "a pose (a run over part of a log)");
  m.def(
      "ate",
      [](const Rows& estimate, const Rows& reference, double time_tolerance) {
        return AteDict(
            AbsoluteTrajectoryError(TrajectoryFrom(estimate), TrajectoryFrom(reference),
                                    time_tolerance));
      },
      py::arg("estimate"), py::arg("reference"), py::arg("time_tolerance") = 1e-3,
      "absolute trajectory error after the best rigid alignment, poses paired by time");
  m.def(
      "compare_by_index",
      [](const Rows& estimate, const Rows& reference, int step) {
        const ReferenceComparison c =
            CompareWithReference(TrajectoryFrom(estimate), TrajectoryFrom(reference), step);
        py::dict d;
        d["ate"] = AteDict(c.ate);
        d["rpe"] = RelationsDict(c.rpe);
        return d;
      },
      py::arg("estimate"), py::arg("reference"), py::arg("step") = 1,
      "ATE and RPE (over pairs i, i + step) against a reference of the same poses in order");
  m.def("nees", &Nees, py::arg("error"), py::arg("covariance"),
        "normalised estimation error squared of a pose error (x, y, theta)");
  m.def(
      "anees_band",
      [](int samples, int dof, double confidence) {
        const ChiSquareBand band = AneesBand(samples, dof, confidence);
        return py::make_tuple(band.lo, band.hi);
      },
      py::arg("samples"), py::arg("dof"), py::arg("confidence") = 0.95,
      "two-sided band of a mean of `samples` chi-square(dof) variables");
}

}  // namespace slamkit::python
