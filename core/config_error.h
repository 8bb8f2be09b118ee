// The error for a bad file or option (architecture.md, "Error handling" tier 2).
#pragma once

#include <stdexcept>

namespace markerbench {

// Bad file or option: main prints what() and exits with status 2.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace markerbench
