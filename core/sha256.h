// SHA-256 (FIPS 180-4), for the run fingerprints and the manifest's file hashes.
#pragma once

#include <cstdint>
#include <string>

namespace markerbench {

class Sha256 {
 public:
  Sha256();
  void Update(const std::string& bytes);
  // Lower-case hex digest; the object must not be updated afterwards.
  std::string HexDigest();

 private:
  void Compress(const uint8_t* block);

  uint32_t state_[8];
  uint8_t buffer_[64];
  uint64_t length_bytes_ = 0;
};

// Digest of a string, and of a file's bytes (throws std::runtime_error when unreadable).
std::string Sha256Hex(const std::string& bytes);
std::string Sha256OfFile(const std::string& path);

}  // namespace markerbench
