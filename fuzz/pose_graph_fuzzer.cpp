// ReadPoseGraph (g2o VERTEX_SE2 / EDGE_SE2 and TORO VERTEX2 / EDGE2 lines, plain or gzip).

#include <cstddef>
#include <cstdint>
#include <unordered_set>

#include "fuzz_input.hpp"
#include "harnesses.hpp"
#include "slamkit/io/error.hpp"
#include "slamkit/io/pose_graph_io.hpp"

int slamkit::fuzz::FuzzPoseGraph(const std::uint8_t* data, std::size_t size) {
  using namespace slamkit::fuzz;
  try {
    const slamkit::PoseGraph graph =
        slamkit::ReadPoseGraph(WriteFile("graph.g2o", AsText(data, size)));
    Check(!graph.vertices.empty(), "a pose graph has at least one vertex");
    std::unordered_set<int> ids;
    for (const slamkit::PoseGraphVertex& v : graph.vertices) {
      Check(v.pose.vector().allFinite(), "vertex poses are finite");
      Check(ids.insert(v.id).second, "vertex ids are unique");
    }
    for (const slamkit::PoseGraphEdge& e : graph.edges) {
      Check(ids.contains(e.from) && ids.contains(e.to), "edges join vertices of the graph");
      Check(e.from != e.to, "no edge from a vertex to itself");
      Check(e.measurement.vector().allFinite(), "edge measurements are finite");
      Check(e.information.allFinite() && e.information == e.information.transpose(),
            "information matrices are finite and symmetric");
    }
  } catch (const slamkit::InputError&) {
  }
  return 0;
}
