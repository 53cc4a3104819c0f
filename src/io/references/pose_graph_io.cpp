// 2D pose graphs in the g2o format (Kümmerle et al., ICRA 2011: VERTEX_SE2, EDGE_SE2) and the
// TORO format (Grisetti et al., RSS 2007: VERTEX2, EDGE2, EQUIV), which differ in the order of the
// information entries.

#include "slamkit/io/pose_graph_io.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <array>
#include <charconv>
#include <iterator>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "slamkit/io/atomic_file.hpp"
#include "slamkit/io/error.hpp"
#include "../text/text_records.hpp"

namespace slamkit {
// Named, so that the helpers' names stay apart from the other readers' in a unity batch.
namespace pose_graph_io {
namespace {

constexpr const char* kVertexFields[] = {"id", "x", "y", "theta"};
constexpr const char* kEquivFields[] = {"id1", "id2"};
constexpr const char* kKnownTags = "VERTEX_SE2, EDGE_SE2, VERTEX2, EDGE2, FIX or EQUIV";

// An edge line's layout: its tag, the names of its fields and where its information entries go.
struct EdgeFormat {
  std::string_view tag;
  std::array<const char*, 11> names;
  std::array<std::pair<int, int>, 6> entries;  // (row, column) of fields 5..10
  std::string_view order;                      // the entries' order, for messages
};

constexpr EdgeFormat kG2oEdge = {
    "EDGE_SE2",
    {"id1", "id2", "dx", "dy", "dtheta", "I11", "I12", "I13", "I22", "I23", "I33"},
    {{{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}}},
    "g2o order I11 I12 I13 I22 I23 I33"};
constexpr EdgeFormat kToroEdge = {
    "EDGE2",
    {"id1", "id2", "dx", "dy", "dtheta", "I11", "I12", "I22", "I33", "I13", "I23"},
    {{{0, 0}, {0, 1}, {1, 1}, {2, 2}, {0, 2}, {1, 2}}},
    "TORO order I11 I12 I22 I33 I13 I23"};

// A text line has no control bytes but tab and CR (a binary file has NULs and others early on).
void CheckText(std::string_view line, const std::string& where) {
  for (std::size_t i = 0; i < line.size(); ++i) {
    const auto u = static_cast<unsigned char>(line[i]);
    if ((u < 0x20 && u != '\t' && u != '\r') || u == 0x7f) {
      throw InputError(
          fmt::format("{}: not a text file (byte \\x{:02x} at column {})", where, u, i + 1));
    }
  }
}

// Exactly names.size() fields; an extra one is reported on the last field's name.
void ExpectFields(const text::Fields& fields, std::span<const char* const> names) {
  if (fields.size() > names.size()) {
    fields.Fail({names.back()}, fmt::format("followed by an extra field ('{}'; expected {} fields)",
                                            text::Printable(fields.Text(names.size())), names.size()));
  }
  fields.Expect(names.size(), names);
}

int Id(const text::Fields& fields, std::size_t i, const char* name) {
  const std::string_view text = fields.Text(i);
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) {
    fields.Fail({name}, fmt::format("not an integer id ('{}')", text::Printable(text)));
  }
  return value;
}

// The symmetric matrix of an edge line's six information entries, read in `format`'s order.
Eigen::Matrix3d Symmetric(const text::Fields& fields, const EdgeFormat& format) {
  Eigen::Matrix3d m;
  for (std::size_t k = 0; k < format.entries.size(); ++k) {
    const auto [r, c] = format.entries[k];
    m(r, c) = m(c, r) = fields.Number(5 + k, {format.names[5 + k]});
  }
  return m;
}

bool PositiveDefinite(const Eigen::Matrix3d& m) {
  return Eigen::LLT<Eigen::Matrix3d>(m).info() == Eigen::Success;
}

// The information of an edge line. When an EDGE2 line's entries make no information matrix in
// TORO order but do in g2o order (w20000.txt), the message says so: the file's writer likely
// used the g2o order under the TORO tag.
Eigen::Matrix3d Information(const text::Fields& fields, const EdgeFormat& format) {
  const Eigen::Matrix3d information = Symmetric(fields, format);
  if (PositiveDefinite(information)) return information;
  std::string values;
  for (std::size_t k = 5; k < 11; ++k) values += fmt::format(" {}", fields.Text(k));
  std::string hint;
  if (&format == &kToroEdge && PositiveDefinite(Symmetric(fields, kG2oEdge))) {
    hint = fmt::format("; positive definite in {}: an EDGE_SE2 line under the EDGE2 tag?",
                       kG2oEdge.order);
  }
  fields.Fail({"information"},
              fmt::format("not positive definite ({}:{}){}", format.order, values, hint));
}

// Builds the graph line by line; the checks that need the whole file wait for Finish.
class PoseGraphParser {
 public:
  explicit PoseGraphParser(std::string file) : file_(std::move(file)) {}

  void Parse(const text::Fields& fields, std::string_view tag, int line) {
    if (tag == "VERTEX_SE2" || tag == "VERTEX2") {
      AddVertex(fields, line);
    } else if (tag == kG2oEdge.tag) {
      AddEdge(fields, kG2oEdge, line);
    } else if (tag == kToroEdge.tag) {
      AddEdge(fields, kToroEdge, line);
    } else if (tag == "FIX") {
      if (fields.size() == 0) fields.Fail({"id"}, "missing");
      for (std::size_t i = 0; i < fields.size(); ++i) Id(fields, i, "id");
    } else if (tag == "EQUIV") {
      ExpectFields(fields, kEquivFields);
      Id(fields, 0, "id1");
      Id(fields, 1, "id2");
    } else {
      throw InputError(fmt::format("{}: field 'tag': unknown tag '{}' (expected {})",
                                   fields.where(), text::Printable(tag), kKnownTags));
    }
  }

  PoseGraph Finish();

 private:
  // Where an edge came from, for the errors found at the end of the file.
  struct EdgeLine {
    std::string_view tag;  // an EdgeFormat's (the line's own text is gone by then)
    int line = 0;
  };

  void AddVertex(const text::Fields& fields, int line);
  void AddEdge(const text::Fields& fields, const EdgeFormat& format, int line);
  void CheckEdgeEnds() const;
  void AddIdentityVertices();

  std::string file_;
  PoseGraph graph_;
  std::unordered_map<int, int> vertex_lines_;  // vertex id -> the line of its VERTEX record
  std::vector<EdgeLine> edge_lines_;           // parallel to graph_.edges
};

void PoseGraphParser::AddVertex(const text::Fields& fields, int line) {
  ExpectFields(fields, kVertexFields);
  PoseGraphVertex vertex;
  vertex.id = Id(fields, 0, "id");
  const auto [it, added] = vertex_lines_.emplace(vertex.id, line);
  if (!added) {
    fields.Fail({"id"},
                fmt::format("duplicate vertex id {} (first on line {})", vertex.id, it->second));
  }
  vertex.pose =
      Pose2(fields.Number(1, {"x"}), fields.Number(2, {"y"}), fields.Number(3, {"theta"}));
  graph_.vertices.push_back(vertex);
}

void PoseGraphParser::AddEdge(const text::Fields& fields, const EdgeFormat& format, int line) {
  ExpectFields(fields, format.names);
  PoseGraphEdge edge;
  edge.from = Id(fields, 0, "id1");
  edge.to = Id(fields, 1, "id2");
  if (edge.from == edge.to) {
    fields.Fail({"id2"}, fmt::format("an edge from vertex {} to itself", edge.from));
  }
  edge.measurement =
      Pose2(fields.Number(2, {"dx"}), fields.Number(3, {"dy"}), fields.Number(4, {"dtheta"}));
  edge.information = Information(fields, format);
  graph_.edges.push_back(edge);
  edge_lines_.push_back({format.tag, line});
}

void PoseGraphParser::CheckEdgeEnds() const {
  for (std::size_t i = 0; i < graph_.edges.size(); ++i) {
    const PoseGraphEdge& edge = graph_.edges[i];
    for (const auto& [id, name] : {std::pair{edge.from, "id1"}, std::pair{edge.to, "id2"}}) {
      if (vertex_lines_.contains(id)) continue;
      throw InputError(fmt::format(
          "{}:{}: {} field '{}': no VERTEX line for vertex {} (the file gives the initial "
          "values of {} other vertices: all or none)",
          file_, edge_lines_[i].line, edge_lines_[i].tag, name, id, vertex_lines_.size()));
    }
  }
}

void PoseGraphParser::AddIdentityVertices() {
  std::set<int> ids;
  for (const PoseGraphEdge& edge : graph_.edges) ids.insert({edge.from, edge.to});
  graph_.vertices.reserve(ids.size());
  for (const int id : ids) graph_.vertices.push_back({id, Pose2()});
}

PoseGraph PoseGraphParser::Finish() {
  if (graph_.vertices.empty() && graph_.edges.empty()) {
    throw InputError(file_ +
                     ": no vertex and no edge (expected a 2D pose graph: g2o VERTEX_SE2 and "
                     "EDGE_SE2 lines, or TORO VERTEX2 and EDGE2 lines)");
  }
  if (graph_.vertices.empty()) {
    AddIdentityVertices();
  } else {
    CheckEdgeEnds();
  }
  return std::move(graph_);
}

}  // namespace
}  // namespace pose_graph_io

PoseGraph ReadPoseGraph(const std::filesystem::path& path) {
  text::LineReader reader(path);
  pose_graph_io::PoseGraphParser parser(path.string());
  std::vector<std::string_view> tokens;
  std::string_view line;
  while (reader.Next(&line)) {
    std::string where = fmt::format("{}:{}", path.string(), reader.line_number());
    if (reader.line_number() == 1 && line.starts_with("\xef\xbb\xbf")) line.remove_prefix(3);
    pose_graph_io::CheckText(line, where);
    text::Tokenize(line, &tokens);
    if (tokens.empty() || tokens[0].starts_with('#')) continue;
    const std::span<const std::string_view> fields(tokens.begin() + 1, tokens.end());
    parser.Parse(text::Fields(std::move(where), tokens[0], fields), tokens[0],
                 reader.line_number());
  }
  return parser.Finish();
}

void WritePoseGraphG2o(const std::filesystem::path& path, const PoseGraph& graph) {
  std::string text;
  auto out = std::back_inserter(text);
  for (const PoseGraphVertex& v : graph.vertices) {
    fmt::format_to(out, "VERTEX_SE2 {} {:.17g} {:.17g} {:.17g}\n", v.id, v.pose.x(), v.pose.y(),
                   v.pose.theta());
  }
  for (const PoseGraphEdge& e : graph.edges) {
    const Pose2& z = e.measurement;
    const Eigen::Matrix3d& I = e.information;
    fmt::format_to(out, "EDGE_SE2 {} {} {:.17g} {:.17g} {:.17g}", e.from, e.to, z.x(), z.y(),
                   z.theta());
    for (const auto& [r, c] : pose_graph_io::kG2oEdge.entries) {
      fmt::format_to(out, " {:.17g}", I(r, c));
    }
    text += '\n';
  }
  WriteFileAtomically(path, text);
}

}  // namespace slamkit
