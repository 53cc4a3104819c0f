#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string_view>

namespace slamkit {

// Writes `path` through `write` into a temporary file beside it and renames it into place, so a
// reader never sees a partial file and a failed write leaves nothing. Throws std::runtime_error
// naming the path when the write fails; the temporary is removed.
void WriteFileAtomically(const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);
void WriteFileAtomically(const std::filesystem::path& path, std::string_view content);

}  // namespace slamkit
