// Readers: CARMEN logs and ROS bags (laser logs), iSAM logs, MRCLAM data sets, trajectories and
// relations. Scans' ranges and MRCLAM's odometry and ground truth are numpy views of the data
// the reader returned (no copy; the view keeps it alive); the rest are small copies.
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <optional>

#include "bindings.hpp"
#include "slamkit/io/carmen_reader.hpp"
#include "slamkit/io/isam_reader.hpp"
#include "slamkit/io/mrclam_reader.hpp"
#include "slamkit/io/relations_reader.hpp"
#include "slamkit/io/rosbag_reader.hpp"
#include "slamkit/io/trajectory_reader.hpp"

namespace slamkit::python {
namespace {

using LaserLog = std::shared_ptr<CarmenLog>;

// `view` made read-only: a view of data a reader returned is not for writing.
py::array ReadOnly(py::array view) {
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return view;
}

// A read-only view of `count` rows of `columns` doubles `stride` bytes apart at `data`, keeping
// `owner` alive.
py::array ReadOnlyView(const double* data, py::ssize_t count, py::ssize_t columns,
                       py::ssize_t stride, py::handle owner) {
  return ReadOnly(py::array(py::dtype::of<double>(), {count, columns},
                            {stride, static_cast<py::ssize_t>(sizeof(double))}, data, owner));
}

template <class T>
py::capsule Owner(std::shared_ptr<T> owner) {
  return py::capsule(new std::shared_ptr<T>(std::move(owner)),
                     [](void* p) { delete static_cast<std::shared_ptr<T>*>(p); });
}

py::array_t<double> PoseArray(const Pose2& p) {
  return py::array_t<double>(3, p.vector().data());
}

void BindLaserLog(py::module_& m) {
  py::class_<LaserScan>(m, "LaserScan", "one planar laser scan (beam i at angle_min + i*increment)")
      .def_readonly("t", &LaserScan::t_s)
      .def_property_readonly(
          "ranges",
          [](py::object self) {
            const LaserScan& s = self.cast<const LaserScan&>();
            return ReadOnly(py::array_t<float>({static_cast<py::ssize_t>(s.ranges_m.size())},
                                               {static_cast<py::ssize_t>(sizeof(float))},
                                               s.ranges_m.data(), self));
          },
          "the ranges [m] as float32, a view of the scan (no copy)")
      .def_readonly("angle_min", &LaserScan::angle_min_rad)
      .def_readonly("angle_increment", &LaserScan::angle_increment_rad)
      .def_readonly("max_range", &LaserScan::max_range_m, "readings at or above it are no return")
      .def_property_readonly("odometry", [](const LaserScan& s) { return PoseArray(s.odometry); })
      .def_property_readonly("logged_pose",
                             [](const LaserScan& s) { return PoseArray(s.logged_pose); })
      .def_property_readonly("laser_offset",
                             [](const LaserScan& s) { return PoseArray(s.laser_offset); });
  py::class_<CarmenLog, LaserLog>(m, "LaserLog", "a laser log's scans, odometry and notes")
      .def("__len__", [](const CarmenLog& log) { return log.scans.size(); })
      .def(
          "__getitem__",
          [](const CarmenLog& log, py::ssize_t i) -> const LaserScan& {
            const auto n = static_cast<py::ssize_t>(log.scans.size());
            if (i < 0) i += n;
            if (i < 0 || i >= n) throw py::index_error("scan index out of range");
            return log.scans[static_cast<std::size_t>(i)];
          },
          py::return_value_policy::reference_internal)
      .def_property_readonly("odometry",
                             [](const CarmenLog& log) { return TrajectoryArray(log.odometry); },
                             "the odometry records: (N, 4) t, x, y, theta")
      .def_readonly("notes", &CarmenLog::notes)
      .def_readonly("no_return_beams", &CarmenLog::no_return_beams);
  m.def(
      "read_carmen",
      [](const std::filesystem::path& path, int max_scans, std::optional<double> max_range) {
        CarmenReadOptions options;
        options.max_range_m = max_range;
        auto log = std::make_shared<CarmenLog>(ReadCarmenLog(path, options));
        if (max_scans > 0 && static_cast<int>(log->scans.size()) > max_scans) {
          log->scans.resize(static_cast<std::size_t>(max_scans));
        }
        return log;
      },
      py::arg("path"), py::arg("max_scans") = 0, py::arg("max_range") = py::none(),
      "a CARMEN log (plain or gzip); InputError names the file, line and field of bad input");
  m.def(
      "read_bag",
      [](const std::filesystem::path& path, const std::string& scan_topic,
         const std::string& odom_topic, bool tf, int max_scans) {
        RosBagReadOptions options;
        options.scan_topic = scan_topic;
        options.odom_topic = odom_topic;
        options.odometry_from_tf = tf;
        auto log = std::make_shared<CarmenLog>(ReadRosBag(path, options));
        if (max_scans > 0 && static_cast<int>(log->scans.size()) > max_scans) {
          log->scans.resize(static_cast<std::size_t>(max_scans));
        }
        return log;
      },
      py::arg("path"), py::arg("scan_topic") = "/scan", py::arg("odom_topic") = "/odom",
      py::arg("tf") = false, py::arg("max_scans") = 0, "a ROS 1 bag as a laser log");
}

void BindIsam(py::module_& m) {
  py::class_<IsamLog, std::shared_ptr<IsamLog>>(m, "IsamLog", "an iSAM-format landmark log")
      .def("__len__", [](const IsamLog& log) { return log.steps.size(); })
      .def_property_readonly("odometry",
                             [](const IsamLog& log) {
                               py::array_t<double> out({static_cast<py::ssize_t>(log.steps.size()),
                                                        py::ssize_t{3}});
                               auto rows = out.mutable_unchecked<2>();
                               for (std::size_t i = 0; i < log.steps.size(); ++i) {
                                 for (int c = 0; c < 3; ++c) {
                                   rows(static_cast<py::ssize_t>(i), c) = log.steps[i].odometry[c];
                                 }
                               }
                               return out;
                             },
                             "each step's dx, dy, dtheta: (N, 3)")
      .def_property_readonly("odometry_covariances",
                             [](const IsamLog& log) {
                               py::array_t<double> out({static_cast<py::ssize_t>(log.steps.size()),
                                                        py::ssize_t{3}, py::ssize_t{3}});
                               for (std::size_t i = 0; i < log.steps.size(); ++i) {
                                 for (int r = 0; r < 3; ++r) {
                                   for (int c = 0; c < 3; ++c) {
                                     out.mutable_at(i, r, c) = log.steps[i].odometry_covariance(r, c);
                                   }
                                 }
                               }
                               return out;
                             },
                             "each step's odometry covariance: (N, 3, 3)")
      .def("sightings",
           [](const IsamLog& log, int step) {
             const auto& s = step < 0 ? log.initial_sightings
                                      : log.steps.at(static_cast<std::size_t>(step)).sightings;
             const auto n = static_cast<py::ssize_t>(s.size());
             py::array_t<double> z({n, py::ssize_t{2}});
             py::array_t<double> covariances({n, py::ssize_t{2}, py::ssize_t{2}});
             py::array_t<long long> ids(n);
             for (std::size_t i = 0; i < s.size(); ++i) {
               z.mutable_at(i, 0) = s[i].z.x();
               z.mutable_at(i, 1) = s[i].z.y();
               for (int r = 0; r < 2; ++r) {
                 for (int c = 0; c < 2; ++c) covariances.mutable_at(i, r, c) = s[i].R(r, c);
               }
               ids.mutable_at(i) = s[i].id;
             }
             return py::make_tuple(z, covariances, ids);
           },
           py::arg("step"),
           "step's sightings (x forward, y left), their covariances and the file's ids; step "
           "-1: the first pose's");
  m.def("read_isam", [](const std::filesystem::path& path) {
    return std::make_shared<IsamLog>(ReadIsamLog(path));
  }, py::arg("path"));
}

void BindMrclam(py::module_& m) {
  static_assert(sizeof(MrclamRobot::Odometry) == 3 * sizeof(double));
  m.def(
      "read_mrclam",
      [](const std::filesystem::path& dir) {
        auto data = std::make_shared<MrclamDataset>(ReadMrclam(dir));
        const py::capsule owner = Owner(data);
        py::list robots;
        for (const MrclamRobot& r : data->robots) {
          py::dict robot;
          robot["subject"] = r.subject;
          robot["odometry"] = ReadOnlyView(reinterpret_cast<const double*>(r.odometry.data()),
                                           static_cast<py::ssize_t>(r.odometry.size()), 3,
                                           sizeof(MrclamRobot::Odometry), owner);
          py::array_t<double> sightings({static_cast<py::ssize_t>(r.sightings.size()),
                                         py::ssize_t{4}});
          for (std::size_t i = 0; i < r.sightings.size(); ++i) {
            const auto& s = r.sightings[i];
            const double row[] = {s.t_s, double(s.subject), s.range_m, s.bearing_rad};
            for (int c = 0; c < 4; ++c) sightings.mutable_at(i, c) = row[c];
          }
          robot["sightings"] = sightings;
          robot["truth"] = TrajectoryArray(r.truth);
          robot["unknown_barcodes"] = r.unknown_barcodes;
          robots.append(robot);
        }
        py::dict landmarks;
        for (const auto& [subject, p] : data->landmarks) {
          landmarks[py::int_(subject)] = py::make_tuple(p.x(), p.y());
        }
        return py::make_tuple(robots, landmarks);
      },
      py::arg("dir"),
      "an MRCLAM folder: (robots, landmarks); each robot's odometry (t, v, omega) is a view of "
      "the data read, its sightings (t, subject, range, bearing) and truth (t, x, y, theta) "
      "arrays");
}

}  // namespace

void BindIo(py::module_& m) {
  BindLaserLog(m);
  BindIsam(m);
  BindMrclam(m);
  m.def("read_trajectory", [](const std::filesystem::path& path) {
    return TrajectoryArray(ReadTrajectory(path));
  }, py::arg("path"), "`t x y theta` lines or TUM: (N, 4) t, x, y, theta");
  m.def("read_relations", [](const std::filesystem::path& path) {
    const std::vector<PoseRelation> relations = ReadRelations(path);
    py::array_t<double> out({static_cast<py::ssize_t>(relations.size()), py::ssize_t{5}});
    for (std::size_t i = 0; i < relations.size(); ++i) {
      const PoseRelation& r = relations[i];
      const double row[] = {r.t1_s, r.t2_s, r.delta.x(), r.delta.y(), r.delta.theta()};
      for (int c = 0; c < 5; ++c) out.mutable_at(i, c) = row[c];
    }
    return out;
  }, py::arg("path"), "Kümmerle et al.'s relations: (N, 5) t1, t2, dx, dy, dtheta");
}

}  // namespace slamkit::python
