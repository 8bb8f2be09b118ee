#include "bench/output_folder.h"

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

}  // namespace markerbench
