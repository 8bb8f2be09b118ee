#include "bench/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>
#include <zstd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace markerbench {
namespace {

// Level 3, zstd's default: ci_noise's frames.csv becomes 3.4× smaller.
constexpr int kZstdLevel = 3;

}  // namespace

AtomicFileWriter::AtomicFileWriter(const std::string& path, Compression compression)
    : path_(path), temporary_(path + ".tmp") {
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw std::runtime_error(temporary_ + ": cannot create: " + std::strerror(errno));
  if (compression == Compression::kZstd) {
    ZSTD_CCtx* context = ZSTD_createCCtx();
    zstd_ = context;
    if (!context ||
        ZSTD_isError(ZSTD_CCtx_setParameter(context, ZSTD_c_compressionLevel, kZstdLevel))) {
      Fail("start compressing", ENOMEM);
    }
  }
}

AtomicFileWriter::~AtomicFileWriter() {
  ZSTD_freeCCtx(static_cast<ZSTD_CCtx*>(zstd_));
  if (fd_ >= 0) {
    ::close(fd_);
    ::unlink(temporary_.c_str());
  }
}

void AtomicFileWriter::Fail(const char* what, int error) {
  if (fd_ >= 0) {
    ::close(fd_);
    ::unlink(temporary_.c_str());
    fd_ = -1;
  }
  throw std::runtime_error(temporary_ + ": cannot " + what + ": " + std::strerror(error));
}

void AtomicFileWriter::WriteRaw(const char* data, size_t size) {
  size_t written = 0;
  while (written < size) {
    const ssize_t n = ::write(fd_, data + written, size - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) Fail("write", n < 0 ? errno : EIO);
    written += static_cast<size_t>(n);
  }
}

void AtomicFileWriter::Compress(std::string_view bytes, bool end) {
  auto* context = static_cast<ZSTD_CCtx*>(zstd_);
  ZSTD_inBuffer in{bytes.data(), bytes.size(), 0};
  buffer_.resize(ZSTD_CStreamOutSize());
  size_t remaining = 0;
  do {
    ZSTD_outBuffer out{buffer_.data(), buffer_.size(), 0};
    remaining = ZSTD_compressStream2(context, &out, &in, end ? ZSTD_e_end : ZSTD_e_continue);
    if (ZSTD_isError(remaining)) Fail("compress", EIO);
    WriteRaw(buffer_.data(), out.pos);
  } while (end ? remaining != 0 : in.pos < in.size);
}

void AtomicFileWriter::Write(std::string_view bytes) {
  if (fd_ < 0) throw std::logic_error(path_ + ": written after Commit()");
  if (zstd_) {
    Compress(bytes, false);
  } else {
    WriteRaw(bytes.data(), bytes.size());
  }
}

void AtomicFileWriter::Commit() {
  if (zstd_) Compress({}, true);
  if (::fsync(fd_) != 0) Fail("sync", errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(temporary_.c_str());
    throw std::runtime_error(temporary_ + ": cannot close: " + std::strerror(error));
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary_.c_str());
    throw std::runtime_error(path_ + ": cannot rename into place: " + std::strerror(error));
  }
}

void WriteFileAtomically(const std::string& path, const std::string& contents) {
  AtomicFileWriter writer(path);
  writer.Write(contents);
  writer.Commit();
}

}  // namespace markerbench
