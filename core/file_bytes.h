// A whole file as bytes.
#pragma once

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace markerbench {

// Throws std::runtime_error naming the file when it cannot be read.
inline std::string ReadFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read");
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

}  // namespace markerbench
