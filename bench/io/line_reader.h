// Reads a text file line by line in bounded memory, decompressing it on the way when its name
// ends in ".zst", so every command reads frames.csv and frames.csv.zst alike.
#pragma once

#include <cstdio>
#include <optional>
#include <string>

namespace markerbench {

class LineReader {
 public:
  // Throws ConfigError when `path` is not a regular file or cannot be opened.
  explicit LineReader(const std::string& path);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  // The next line without its '\n'; false at the end. A last line without '\n' is a line. A
  // damaged or truncated compressed file throws ConfigError naming the file and line.
  bool Next(std::string* line);
  // The number of the line Next() returned last (1 for the first).
  size_t line_number() const { return line_number_; }
  const std::string& path() const { return path_; }

 private:
  bool Fill();  // more text into text_; false at the end of the file

  std::string path_;
  std::FILE* file_ = nullptr;
  void* zstd_ = nullptr;  // ZSTD_DCtx* for a .zst file
  std::string input_;     // compressed bytes read but not yet decompressed
  size_t input_pos_ = 0;
  std::string output_;       // the decoder's output buffer, reused
  bool frame_open_ = false;  // the last frame read has not ended
  std::string text_;
  size_t text_pos_ = 0;
  size_t line_number_ = 0;
};

// Reads the first line of `reader`; throws ConfigError naming the file unless it is `header`
// (which ends in '\n').
void ExpectHeader(LineReader& reader, const std::string& header);

// DIR/NAME or DIR/NAME.zst, whichever exists; nullopt when neither does. Both at once is a
// ConfigError (which one holds the run?).
std::optional<std::string> FindTextFile(const std::string& dir, const std::string& name);

}  // namespace markerbench
