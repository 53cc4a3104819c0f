#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "slamkit/io/error.hpp"
#include "slamkit/io/relations_reader.hpp"
#include "../text/text_records.hpp"

namespace slamkit {
namespace {

constexpr const char* kRelationFields[] = {"t1", "t2", "x", "y", "z", "roll", "pitch", "yaw"};

PoseRelation ParseRelation(const text::Fields& fields) {
  fields.Expect(std::size(kRelationFields), kRelationFields);
  double values[std::size(kRelationFields)];
  for (std::size_t i = 0; i < std::size(kRelationFields); ++i) {
    values[i] = fields.Number(i, {kRelationFields[i]});
  }
  for (std::size_t i : {4, 5, 6}) {
    if (std::abs(values[i]) > text::kOutOfPlaneTolerance) {
      fields.Fail({kRelationFields[i]},
                  fmt::format("must be 0 in a planar relation ('{}')", fields.Text(i)));
    }
  }
  return {values[0], values[1], Pose2(values[2], values[3], values[7])};
}

}  // namespace

std::vector<PoseRelation> ReadRelations(const std::filesystem::path& path) {
  std::vector<PoseRelation> relations;
  text::ForEachRecord(path, [&](const text::Fields& fields) {
    relations.push_back(ParseRelation(fields));
  });
  if (relations.empty()) {
    throw InputError(path.string() +
                     ": no relations (expected `t1 t2 x y z roll pitch yaw` lines)");
  }
  return relations;
}

}  // namespace slamkit
