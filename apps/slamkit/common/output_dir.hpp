#pragma once

#include <filesystem>
#include <string>

namespace slamkit::app {

// A run's output directory (--out), made before the run and put in place after it: the run
// writes into a fresh hidden folder beside it (`.NAME.partial-XXXXXX`), which Commit() renames
// onto `out` in one step (an existing `out` is swapped with it, then removed). So `out` holds
// either its old content or the whole new output, never a mix; a failed run removes its folder
// (an interrupted one leaves it, hidden, beside `out`).
class OutputDir {
 public:
  // Throws InputError naming `out` if it cannot be the output: empty, an existing
  // non-directory, a directory holding other files than an earlier output (no metrics.json),
  // or a place where no folder can be made.
  explicit OutputDir(const std::string& out);
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  ~OutputDir();

  // Where the run writes its files.
  const std::filesystem::path& staging() const { return staging_; }
  // Puts the written output in place of `out`.
  void Commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace slamkit::app
