#include "core/sha256.h"

#include <openssl/evp.h>

#include <cstdio>
#include <new>
#include <stdexcept>

#include "core/file_bytes.h"

namespace markerbench {

struct Sha256::Context {
  EVP_MD_CTX* md = EVP_MD_CTX_new();
  ~Context() { EVP_MD_CTX_free(md); }
};

Sha256::Sha256() : context_(std::make_unique<Context>()) {
  if (!context_->md) throw std::bad_alloc();
  if (EVP_DigestInit_ex(context_->md, EVP_sha256(), nullptr) != 1) {
    throw std::runtime_error("SHA-256: OpenSSL could not start a digest");
  }
}

Sha256::~Sha256() = default;

void Sha256::Update(const std::string& bytes) {
  if (EVP_DigestUpdate(context_->md, bytes.data(), bytes.size()) != 1) {
    throw std::runtime_error("SHA-256: OpenSSL could not hash the input");
  }
}

std::string Sha256::HexDigest() {
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_DigestFinal_ex(context_->md, digest, &size) != 1) {
    throw std::runtime_error("SHA-256: OpenSSL could not finish the digest");
  }
  std::string hex;
  for (unsigned int i = 0; i < size; ++i) {
    char part[3];
    std::snprintf(part, sizeof(part), "%02x", digest[i]);
    hex += part;
  }
  return hex;
}

std::string Sha256Hex(const std::string& bytes) {
  Sha256 sha;
  sha.Update(bytes);
  return sha.HexDigest();
}

std::string Sha256OfFile(const std::string& path) { return Sha256Hex(ReadFileBytes(path)); }

}  // namespace markerbench
