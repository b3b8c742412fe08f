// An output file is written completely or not at all: the bytes go to a temporary
// file beside the target, which is renamed over the target only once it is complete.
#pragma once

#include <functional>
#include <string>

namespace shadowref {

// Calls write(tempPath) with a fresh, empty, uniquely named file "path.tmp-<pid>-<n>" in the
// target's directory (same file system, so the final rename is atomic), then renames it to path.
// If write throws, or creating or renaming fails, the temporary file is removed and a
// std::runtime_error naming path is thrown; an existing file at path is left untouched.
void writeFileAtomically(const std::string& path,
                         const std::function<void(const std::string& tempPath)>& write);

}  // namespace shadowref
