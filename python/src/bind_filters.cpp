// Filters through their interfaces: LandmarkSlamFilter (EkfSlam, FastSlam with the iSAM log's
// models: odometry increments in, relative-point sightings x forward, y left) and GridSlam (the
// grid RBPF or the pose graph, laser scans in).
#include <pybind11/eigen.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <optional>

#include "bindings.hpp"
#include "slamkit/core/cpu.hpp"
#include "slamkit/filters/ekf_slam/ekf_slam.hpp"
#include "slamkit/filters/fastslam/fastslam.hpp"
#include "slamkit/filters/grid_slam_factory.hpp"
#include "slamkit/io/grid_writers.hpp"
#include "slamkit/models/odometry.hpp"
#include "slamkit/models/relative_point.hpp"
#include "slamkit/runners/grid/grid_config.hpp"
#include "slamkit/runners/landmark/filter_choice.hpp"
#include "slamkit/runners/landmark/isam_config.hpp"
#include "slamkit/runners/landmark/isam_run.hpp"

namespace slamkit::python {
namespace {

using Matrix = Eigen::MatrixXd;

IsamRunParams IsamParams(const std::optional<std::filesystem::path>& config) {
  return config ? LoadIsamConfig(*config) : IsamRunParams{};
}

const char* KindName(AssociationDecision::Kind kind) {
  switch (kind) {
    case AssociationDecision::Kind::kMatched: return "matched";
    case AssociationDecision::Kind::kNew: return "new";
    case AssociationDecision::Kind::kDropped: return "dropped";
  }
  return "dropped";
}

// Sightings (N, 2) x forward, y left, with covariances (N, 2, 2) and optional ids.
py::list Update(LandmarkSlamFilter& filter, const py::array_t<double, py::array::forcecast>& z,
                const py::array_t<double, py::array::forcecast>& covariances,
                const std::optional<std::vector<long long>>& ids) {
  if (z.ndim() != 2 || z.shape(1) != 2 || covariances.ndim() != 3 ||
      covariances.shape(0) != z.shape(0) || covariances.shape(1) != 2 ||
      covariances.shape(2) != 2 || (ids && static_cast<py::ssize_t>(ids->size()) != z.shape(0))) {
    throw py::value_error("update: z is (N, 2), covariances (N, 2, 2), ids N long");
  }
  std::vector<PointObservation> observations(static_cast<std::size_t>(z.shape(0)));
  for (py::ssize_t i = 0; i < z.shape(0); ++i) {
    PointObservation& o = observations[static_cast<std::size_t>(i)];
    o.z = {z.at(i, 0), z.at(i, 1)};
    o.R << covariances.at(i, 0, 0), covariances.at(i, 0, 1), covariances.at(i, 1, 0),
        covariances.at(i, 1, 1);
    o.id = ids ? (*ids)[static_cast<std::size_t>(i)] : kNoLandmark;
  }
  py::list out;
  for (const AssociationDecision& d : filter.Update(observations)) {
    out.append(py::make_tuple(KindName(d.kind), d.landmark));
  }
  return out;
}

void BindLandmarkFilters(py::module_& m) {
  py::class_<LandmarkSlamFilter, std::shared_ptr<LandmarkSlamFilter>>(
      m, "LandmarkSlamFilter", "what every point-landmark SLAM filter offers")
      .def(
          "reset",
          [](LandmarkSlamFilter& f, const Eigen::Vector3d& pose, const Eigen::Matrix3d& cov) {
            f.Reset(Pose2(pose), cov);
          },
          py::arg("pose") = Eigen::Vector3d::Zero(), py::arg("covariance") = Eigen::Matrix3d::Zero())
      .def(
          "predict",
          [](LandmarkSlamFilter& f, const Eigen::Vector3d& u, const Eigen::Matrix3d& q) {
            const ControlCovariance noise = q;
            f.Predict(Control(u), 0.0, &noise);
          },
          py::arg("increment"), py::arg("covariance"),
          "moves the pose by an odometry increment (dx, dy, dtheta) with its covariance")
      .def("update", &Update, py::arg("z"), py::arg("covariances"), py::arg("ids") = py::none(),
           "associates and applies one scan's sightings; [(kind, landmark)] per sighting")
      .def_property_readonly("pose", [](const LandmarkSlamFilter& f) {
        return Eigen::Vector3d(f.PoseEstimate().vector());
      })
      .def_property_readonly("pose_covariance", &LandmarkSlamFilter::PoseCovariance)
      .def_property_readonly("num_landmarks", &LandmarkSlamFilter::NumLandmarks)
      .def(
          "landmarks",
          [](const LandmarkSlamFilter& f) {
            const LandmarkMap map = f.Map();
            Matrix positions(map.landmarks.size(), 2);
            py::array_t<double> covariances(
                {static_cast<py::ssize_t>(map.landmarks.size()), py::ssize_t{2}, py::ssize_t{2}});
            for (std::size_t i = 0; i < map.landmarks.size(); ++i) {
              positions.row(static_cast<Eigen::Index>(i)) = map.landmarks[i].position_m;
              for (int r = 0; r < 2; ++r) {
                for (int c = 0; c < 2; ++c) {
                  covariances.mutable_at(i, r, c) = map.landmarks[i].covariance(r, c);
                }
              }
            }
            return py::make_tuple(positions, covariances);
          },
          "(positions (N, 2), covariances (N, 2, 2))");
  py::class_<EkfSlam, LandmarkSlamFilter, std::shared_ptr<EkfSlam>>(m, "EkfSlam")
      .def(py::init([](const std::optional<std::filesystem::path>& config) {
             return std::make_shared<EkfSlam>(IsamParams(config).ekf,
                                              std::make_unique<OdometryModel>(),
                                              std::make_unique<RelativePointModel>());
           }),
           py::arg("config") = py::none(),
           "EKF-SLAM with odometry increments and relative-point sightings; config: an iSAM run "
           "config (configs/victoria_park.yaml), else the defaults")
      .def_property_readonly("covariance", &EkfSlam::Covariance, "the full covariance (a copy)")
      .def_property_readonly("state", &EkfSlam::State);
  py::class_<FastSlam, LandmarkSlamFilter, std::shared_ptr<FastSlam>>(m, "FastSlam")
      .def(py::init([](const std::optional<std::filesystem::path>& config,
                       const std::string& version, int particles, std::uint64_t seed,
                       int threads) {
             const IsamRunParams params = IsamParams(config);
             FastSlamParams fastslam =
                 FastSlamParamsFor(ParseFilterKind(version), particles, params.ekf);
             fastslam.seed = seed;
             fastslam.threads = threads > 0 ? threads : UsableCpuCount();
             return std::make_shared<FastSlam>(IsamFastSlamParams(params, fastslam),
                                               std::make_unique<OdometryModel>(),
                                               std::make_unique<RelativePointModel>());
           }),
           py::arg("config") = py::none(), py::arg("version") = "fastslam2",
           py::arg("particles") = 100, py::arg("seed") = 1, py::arg("threads") = 0,
           "FastSLAM 1.0 or 2.0 with the same models and the iSAM config's association");
}

py::dict MapDict(const OccupancyGrid& grid) {
  const OccupancyImage image = RenderOccupancyImage(grid);
  py::array_t<std::uint8_t> pixels({image.height, image.width});
  std::copy(image.pixels.begin(), image.pixels.end(), pixels.mutable_data());
  py::dict out;
  out["image"] = pixels;
  out["resolution"] = image.resolution_m;
  out["origin"] = py::make_tuple(image.origin_m.x(), image.origin_m.y());
  return out;
}

void BindGridSlam(py::module_& m) {
  py::class_<GridSlam, std::shared_ptr<GridSlam>>(m, "GridSlam",
                                                  "laser SLAM on occupancy grids: scans in")
      .def(py::init([](const std::optional<std::filesystem::path>& config) {
             const GridSlamConfig c = config ? LoadGridConfig(*config) : GridSlamConfig{};
             return std::shared_ptr<GridSlam>(MakeGridSlam(c));
           }),
           py::arg("config") = py::none(),
           "the filter a grid config names (configs/grid.yaml; backend rbpf or graph), else "
           "the grid RBPF with its defaults")
      .def("process_scan", &GridSlam::ProcessScan, py::arg("scan"),
           py::call_guard<py::gil_scoped_release>(), "True when the scan updated the estimate")
      .def("finish", &GridSlam::Finish, py::call_guard<py::gil_scoped_release>())
      .def_property_readonly("pose",
                             [](GridSlam& s) { return Eigen::Vector3d(s.CurrentPose().vector()); })
      .def("trajectory", [](GridSlam& s) { return TrajectoryArray(s.BestTrajectory()); },
           "one pose per processed scan: (N, 4) t, x, y, theta")
      .def("map", [](const GridSlam& s) { return MapDict(s.BestMap()); },
           "the best map as map_server's image (free 254, occupied 0, unknown 205; top row = "
           "largest y) with its resolution and origin")
      .def("check_health", &GridSlam::CheckOutputHealth);
}

}  // namespace

void BindFilters(py::module_& m) {
  BindLandmarkFilters(m);
  BindGridSlam(m);
}

}  // namespace slamkit::python
