#include "common/output_dir.hpp"

#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <string>
#include <system_error>

#include <fmt/format.h>

#include "slamkit/io/error.hpp"

namespace slamkit::app {

OutputDir::OutputDir(const std::string& out) {
  namespace fs = std::filesystem;
  if (out.empty()) throw InputError("--out: the output directory is empty");
  std::error_code ec;
  fs::path target = fs::absolute(fs::path(out), ec).lexically_normal();
  if (ec) throw InputError(fmt::format("--out {}: {}", out, ec.message()));
  if (!target.has_filename()) target = target.parent_path();  // "out/" and "."
  if (target == target.root_path()) {
    throw InputError(fmt::format("--out {}: cannot replace the root directory", out));
  }
  const fs::file_status status = fs::status(target, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) {
      throw InputError(fmt::format("--out {}: exists and is not a directory", out));
    }
    // The run replaces the whole directory: only an empty one or an earlier output.
    const bool empty = fs::is_empty(target, ec);
    if (!ec && !empty && !fs::exists(target / "metrics.json")) {
      throw InputError(fmt::format(
          "--out {}: exists and holds other files than an earlier slamkit output (no "
          "metrics.json); the run would replace it: give a new directory",
          out));
    }
  }
  target_ = target;
  fs::create_directories(target.parent_path(), ec);
  if (ec) throw InputError(fmt::format("--out {}: cannot create it: {}", out, ec.message()));
  // The run writes beside the target, then renames: either the old output or the whole new one.
  std::string staging =
      (target.parent_path() / ("." + target.filename().string() + ".partial-XXXXXX")).string();
  if (mkdtemp(staging.data()) == nullptr) {
    throw InputError(fmt::format("--out {}: cannot create it: {}", out, std::strerror(errno)));
  }
  const mode_t mask = umask(0);  // mkdtemp makes 0700: give it the mode mkdir would
  umask(mask);
  chmod(staging.c_str(), 0777 & ~mask);
  staging_ = staging;
}

OutputDir::~OutputDir() {
  if (committed_) return;
  std::error_code ec;
  std::filesystem::remove_all(staging_, ec);
}

void OutputDir::Commit() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(target_, ec)) {
    fs::rename(staging_, target_);  // throws (exit 1) with both names
  } else {
    // Swap the two in one step, then remove the old output (now at the staging name).
    if (renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, target_.c_str(), RENAME_EXCHANGE) != 0) {
      throw std::system_error(errno, std::generic_category(),
                              fmt::format("cannot move {} to {}", staging_.string(),
                                          target_.string()));
    }
  }
  committed_ = true;
  fs::remove_all(staging_, ec);
}

}  // namespace slamkit::app
