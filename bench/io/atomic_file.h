// Files that must survive a crash or a full disk: written to a temporary file beside the
// target, flushed, fsynced and renamed over it, so a reader sees the old or the new contents
// and never a truncated file. An AtomicFileWriter may compress what it writes with zstd (one
// zstd frame: `zstd -d`, pandas and polars read it).
#pragma once

#include <string>
#include <string_view>

namespace markerbench {

// Streams a file into place: Write() any number of times, then Commit(). Destroyed without
// Commit() (an exception on the way), it removes its temporary file and leaves the target as
// it was. Every failing step throws std::runtime_error naming the path and the errno text.
enum class Compression { kNone, kZstd };

class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(const std::string& path, Compression compression = Compression::kNone);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

  void Write(std::string_view bytes);
  void Commit();

 private:
  void WriteRaw(const char* data, size_t size);
  void Compress(std::string_view bytes, bool end);
  [[noreturn]] void Fail(const char* what, int error);

  std::string path_;
  std::string temporary_;
  int fd_ = -1;
  void* zstd_ = nullptr;  // ZSTD_CCtx* when compressing
  std::string buffer_;
};

// `contents` as they are, into place.
void WriteFileAtomically(const std::string& path, const std::string& contents);

}  // namespace markerbench
