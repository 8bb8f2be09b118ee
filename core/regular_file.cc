#include "core/regular_file.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "core/config_error.h"

namespace markerbench {

void RequireRegularFile(const std::string& path) {
  struct stat status {};
  if (stat(path.c_str(), &status) != 0) {
    throw ConfigError(path + ": cannot open the file: " + std::strerror(errno));
  }
  if (S_ISREG(status.st_mode)) return;
  const char* kind = S_ISDIR(status.st_mode)    ? "a directory"
                     : S_ISFIFO(status.st_mode) ? "a FIFO"
                     : S_ISCHR(status.st_mode)  ? "a character device"
                     : S_ISBLK(status.st_mode)  ? "a block device"
                     : S_ISSOCK(status.st_mode) ? "a socket"
                                                : "not a file";
  throw ConfigError(path + ": expected a regular file, got " + kind);
}

}  // namespace markerbench
