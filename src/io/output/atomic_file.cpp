#include "slamkit/io/atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace slamkit {
namespace {

std::filesystem::path TemporaryPath(const std::filesystem::path& path) {
  std::filesystem::path tmp = path;
  tmp += ".tmp." + std::to_string(::getpid());
  return tmp;
}

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& reason) {
  throw std::runtime_error("cannot write '" + path.string() + "': " + reason);
}

// Writes and closes the temporary, throwing on any stream failure.
void WriteTemporary(const std::filesystem::path& path, const std::filesystem::path& tmp,
                    const std::function<void(std::ostream&)>& write) {
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  if (!out) Fail(path, "cannot create '" + tmp.string() + "'");
  try {
    write(out);
  } catch (const std::exception& e) {
    Fail(path, e.what());
  }
  out.flush();
  if (!out) Fail(path, "write failed");
  out.close();
  if (!out) Fail(path, "close failed");
}

}  // namespace

void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write) {
  const std::filesystem::path tmp = TemporaryPath(path);
  try {
    WriteTemporary(path, tmp, write);
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) Fail(path, "cannot rename '" + tmp.string() + "': " + ec.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

void WriteFileAtomically(const std::filesystem::path& path, std::string_view content) {
  WriteFileAtomically(path, [content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

}  // namespace slamkit
