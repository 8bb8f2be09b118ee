// Files a user names must be regular files: a directory reads as an odd error, a FIFO blocks
// the reader forever and a device reads as empty or endless.
#pragma once

#include <string>

namespace markerbench {

// Throws ConfigError naming `path` when it is missing or not a regular file (symbolic links
// are followed).
void RequireRegularFile(const std::string& path);

}  // namespace markerbench
