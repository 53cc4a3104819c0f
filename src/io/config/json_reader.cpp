#include "slamkit/io/json_reader.hpp"

#include <fstream>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"

namespace slamkit {

nlohmann::json ReadJson(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open file");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not JSON: {}", path.string(), e.what()));
  }
}

}  // namespace slamkit
