#include "bench/io/line_reader.h"

#include <zstd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/config_error.h"
#include "core/regular_file.h"

namespace fs = std::filesystem;

namespace markerbench {
namespace {

constexpr size_t kChunkBytes = 1 << 16;

}  // namespace

LineReader::LineReader(const std::string& path) : path_(path) {
  RequireRegularFile(path);
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) throw ConfigError(path + ": cannot read: " + std::strerror(errno));
  if (path.size() >= 4 && path.compare(path.size() - 4, 4, ".zst") == 0) {
    zstd_ = ZSTD_createDCtx();
    if (!zstd_) {
      std::fclose(file_);
      throw std::bad_alloc();
    }
  }
}

LineReader::~LineReader() {
  ZSTD_freeDCtx(static_cast<ZSTD_DCtx*>(zstd_));
  std::fclose(file_);
}

bool LineReader::Fill() {
  text_.erase(0, text_pos_);
  text_pos_ = 0;
  if (!zstd_) {
    char chunk[kChunkBytes];
    const size_t n = std::fread(chunk, 1, sizeof(chunk), file_);
    if (n == 0 && std::ferror(file_)) throw ConfigError(path_ + ": cannot read");
    text_.append(chunk, n);
    return n > 0;
  }
  output_.resize(ZSTD_DStreamOutSize());
  while (true) {
    bool at_end = false;
    if (input_pos_ == input_.size()) {
      input_.resize(ZSTD_DStreamInSize());
      const size_t n = std::fread(input_.data(), 1, input_.size(), file_);
      if (n == 0 && std::ferror(file_)) throw ConfigError(path_ + ": cannot read");
      input_.resize(n);
      input_pos_ = 0;
      at_end = n == 0;
    }
    // At the end of the file the decoder may still hold output of the last frame.
    ZSTD_inBuffer in{input_.data(), input_.size(), input_pos_};
    ZSTD_outBuffer out{output_.data(), output_.size(), 0};
    const size_t hint = ZSTD_decompressStream(static_cast<ZSTD_DCtx*>(zstd_), &out, &in);
    if (ZSTD_isError(hint)) {
      throw ConfigError(path_ + ":" + std::to_string(line_number_ + 1) +
                        ": not a valid zstd file: " + ZSTD_getErrorName(hint));
    }
    if (in.pos > input_pos_ || out.pos > 0) frame_open_ = hint != 0;
    input_pos_ = in.pos;
    text_.append(output_.data(), out.pos);
    if (out.pos > 0) return true;
    if (at_end) {
      if (frame_open_) {
        throw ConfigError(path_ + ":" + std::to_string(line_number_ + 1) +
                          ": the compressed file ends inside a zstd frame (truncated)");
      }
      return false;
    }
  }
}

bool LineReader::Next(std::string* line) {
  size_t end = text_.find('\n', text_pos_);
  while (end == std::string::npos) {
    const size_t scanned = text_.size() - text_pos_;
    if (!Fill()) {
      if (text_pos_ == text_.size()) return false;
      *line = text_.substr(text_pos_);
      text_pos_ = text_.size();
      ++line_number_;
      return true;
    }
    end = text_.find('\n', scanned);
  }
  line->assign(text_, text_pos_, end - text_pos_);
  text_pos_ = end + 1;
  ++line_number_;
  return true;
}

void ExpectHeader(LineReader& reader, const std::string& header) {
  std::string line;
  if (!reader.Next(&line) || line + '\n' != header) {
    throw ConfigError(reader.path() + ":1: expected the header '" +
                      header.substr(0, header.size() - 1) + "'");
  }
}

std::optional<std::string> FindTextFile(const std::string& dir, const std::string& name) {
  const std::string plain = (fs::path(dir) / name).string();
  const std::string compressed = plain + ".zst";
  const bool has_plain = fs::exists(plain);
  const bool has_compressed = fs::exists(compressed);
  if (has_plain && has_compressed) {
    throw ConfigError(dir + ": holds both " + name + " and " + name +
                      ".zst; remove the one that is not the run's");
  }
  if (has_plain) return plain;
  if (has_compressed) return compressed;
  return std::nullopt;
}

}  // namespace markerbench
