#include "bench/io/data_dir.h"

#include <filesystem>
#include <stdexcept>

namespace markerbench {

std::string DataDir() {
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe");
  return (executable.parent_path().parent_path() / "share" / "markerbench")
      .lexically_normal()
      .string();
}

std::string DataFile(const std::string& relative_path) {
  const std::string path = DataDir() + "/" + relative_path;
  if (!std::filesystem::exists(path)) {
    throw std::runtime_error(path + ": missing; markerbench's data is not installed beside it");
  }
  return path;
}

}  // namespace markerbench
