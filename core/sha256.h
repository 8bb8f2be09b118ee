// SHA-256 for the run fingerprints and the manifest's file hashes: OpenSSL's libcrypto (EVP),
// behind a small interface so that callers do not see OpenSSL.
#pragma once

#include <memory>
#include <string>

namespace markerbench {

class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;

  void Update(const std::string& bytes);
  // Lower-case hex digest; the object must not be updated afterwards.
  std::string HexDigest();

 private:
  struct Context;
  std::unique_ptr<Context> context_;
};

// Digest of a string, and of a file's bytes (throws std::runtime_error when unreadable).
std::string Sha256Hex(const std::string& bytes);
std::string Sha256OfFile(const std::string& path);

}  // namespace markerbench
