// Whole runs as the command line does them, for scripts that want its figures.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>

#include "bindings.hpp"
#include "slamkit/core/cpu.hpp"
#include "slamkit/io/isam_reader.hpp"
#include "slamkit/runners/landmark/filter_choice.hpp"
#include "slamkit/runners/landmark/isam_config.hpp"
#include "slamkit/runners/landmark/isam_run.hpp"
#include "slamkit/runners/landmark/outputs.hpp"

namespace slamkit::python {

void BindRuns(py::module_& m) {
  m.def(
      "run_isam",
      [](const std::filesystem::path& path, const std::optional<std::filesystem::path>& config,
         const std::string& filter, int particles, std::uint64_t seed) {
        const IsamRunParams params = config ? LoadIsamConfig(*config) : IsamRunParams{};
        const IsamLog log = ReadIsamLog(path);
        IsamRunResult result;
        {
          const py::gil_scoped_release unlocked;
          const FilterKind kind = ParseFilterKind(filter);
          if (kind == FilterKind::kEkf) {
            result = RunEkfSlamOnIsam(log, params);
          } else {
            FastSlamParams fastslam = FastSlamParamsFor(kind, particles, params.ekf);
            fastslam.seed = seed;
            fastslam.threads = UsableCpuCount();
            result = RunFastSlamOnIsam(log, params, fastslam);
          }
        }
        nlohmann::json metrics = IsamMetrics(result, params);
        metrics["filter"] = filter;
        return py::make_tuple(FromJson(metrics), TrajectoryArray(result.estimate));
      },
      py::arg("path"), py::arg("config") = py::none(), py::arg("filter") = "ekf",
      py::arg("particles") = 100, py::arg("seed") = 1,
      "`slamkit run --isam PATH [--config CONFIG] [--filter F]`: (metrics as its metrics.json, "
      "the estimate (N, 4) with t the pose index)");
}

}  // namespace slamkit::python
