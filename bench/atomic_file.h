// Files that must survive a crash or a full disk: written to a temporary file beside the
// target, flushed, fsynced and renamed over it, so a reader sees the old or the new contents
// and never a truncated file.
#pragma once

#include <string>

namespace markerbench {

// Throws std::runtime_error naming the path and the errno text when any step fails; the
// target is then left as it was.
void WriteFileAtomically(const std::string& path, const std::string& contents);

}  // namespace markerbench
