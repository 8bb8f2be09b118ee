#include "bench/io/output_folder.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <stdexcept>
#include <system_error>

#include "core/config_error.h"

namespace markerbench {

void CreateOutputFolder(const std::string& dir) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(dir, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_directory(status)) {
    throw ConfigError(dir + ": expected an output folder, but it is a file");
  }
  std::filesystem::create_directories(dir, error);
  if (error)
    throw std::runtime_error(dir + ": cannot create the output folder: " + error.message());
}

void CreateEmptyOutputFolder(const std::string& dir, bool overwrite) {
  CreateOutputFolder(dir);
  if (std::filesystem::is_empty(dir)) return;
  if (!overwrite) {
    throw ConfigError(dir +
                      ": not empty; choose a new --out, or pass --overwrite to replace the "
                      "dataset markerbench rendered there");
  }
  if (!std::filesystem::exists(std::filesystem::path(dir) / "dataset.json")) {
    throw ConfigError(dir +
                      ": --overwrite empties only a folder markerbench rendered (with "
                      "dataset.json); this one holds something else");
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::filesystem::remove_all(entry.path());
  }
}

void LockOutputFolder(const std::string& out_dir) {
  CreateOutputFolder(out_dir);
  const std::string path = out_dir + "/markerbench.lock";
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw std::system_error(errno, std::generic_category(), path + ": cannot open");
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd);
    if (error == EWOULDBLOCK) {
      throw ConfigError(path + ": another markerbench sweep or merge is writing into " + out_dir +
                        "; wait for it or choose another --out");
    }
    throw std::system_error(error, std::generic_category(), path + ": cannot lock");
  }
  // The descriptor stays open (and the lock held) for the life of the process.
}

}  // namespace markerbench
