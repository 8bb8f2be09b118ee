// LineReader and AtomicFileWriter: plain and zstd files round-trip line for line, in pieces
// larger than their buffers; damaged compressed files are located errors.
#include "bench/io/line_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "bench/io/atomic_file.h"
#include "core/config_error.h"
#include "core/file_bytes.h"
#include "core/test_files.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;

// Lines of random lengths (0 to 3000 bytes), about 3 MB: several zstd blocks and many
// reader buffers.
std::vector<std::string> SomeLines() {
  std::mt19937 random(7);
  std::vector<std::string> lines;
  for (int i = 0; i < 2000; ++i) {
    std::string line = std::to_string(i) + ",";
    const int length = std::uniform_int_distribution<int>(0, 3000)(random);
    for (int k = 0; k < length; ++k) line += static_cast<char>('a' + random() % 26);
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> ReadAll(const std::string& path) {
  LineReader reader(path);
  std::vector<std::string> lines;
  std::string line;
  while (reader.Next(&line)) {
    lines.push_back(line);
    EXPECT_EQ(reader.line_number(), lines.size());
  }
  return lines;
}

std::string Write(const std::string& path, const std::vector<std::string>& lines) {
  const bool zstd = path.size() > 4 && path.substr(path.size() - 4) == ".zst";
  AtomicFileWriter writer(path, zstd ? Compression::kZstd : Compression::kNone);
  for (const std::string& line : lines) writer.Write(line + "\n");
  writer.Commit();
  return path;
}

TEST(LineReaderTest, PlainAndCompressedFilesRoundTrip) {
  const std::vector<std::string> lines = SomeLines();
  const std::string dir = std::filesystem::path(WriteTestFile("x", "")).parent_path().string();
  const std::string plain = Write(dir + "/lines.csv", lines);
  const std::string packed = Write(dir + "/lines.csv.zst", lines);
  EXPECT_EQ(ReadAll(plain), lines);
  EXPECT_EQ(ReadAll(packed), lines);
  EXPECT_LT(std::filesystem::file_size(packed), std::filesystem::file_size(plain));
  EXPECT_FALSE(std::filesystem::exists(packed + ".tmp"));
  // A zstd file is a sequence of frames: two files end to end read as one.
  const std::string both = dir + "/both.csv.zst";
  std::ofstream(both, std::ios::binary) << ReadFileBytes(packed) << ReadFileBytes(packed);
  std::vector<std::string> twice = lines;
  twice.insert(twice.end(), lines.begin(), lines.end());
  EXPECT_EQ(ReadAll(both), twice);
}

TEST(LineReaderTest, ALastLineWithoutNewlineIsALine) {
  EXPECT_EQ(ReadAll(WriteTestFile("last.csv", "a\n\nb")), (std::vector<std::string>{"a", "", "b"}));
  EXPECT_TRUE(ReadAll(WriteTestFile("empty.csv", "")).empty());
}

TEST(LineReaderTest, DamagedCompressedFilesAreLocatedErrors) {
  const std::string dir = std::filesystem::path(WriteTestFile("x", "")).parent_path().string();
  const std::string bytes = ReadFileBytes(Write(dir + "/whole.csv.zst", SomeLines()));
  const std::string truncated = dir + "/truncated.csv.zst";
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  EXPECT_THAT([&] { ReadAll(truncated); },
              ::testing::ThrowsMessage<ConfigError>(HasSubstr("truncated")));
  const std::string plain_named = WriteTestFile("notzstd.csv.zst", "frame,tracker\n1,a\n");
  EXPECT_THAT(
      [&] { ReadAll(plain_named); },
      ::testing::ThrowsMessage<ConfigError>(HasSubstr("notzstd.csv.zst:1: not a valid zstd file")));
  EXPECT_THROW(LineReader(dir + "/missing.csv"), ConfigError);
  EXPECT_THROW(LineReader{dir}, ConfigError);  // a folder
}

TEST(LineReaderTest, FindTextFileTakesEitherFormButNotBoth) {
  const std::string dir =
      std::filesystem::path(WriteTestFile("x", "")).parent_path().string() + "/find";
  std::filesystem::create_directories(dir);
  EXPECT_EQ(FindTextFile(dir, "frames.csv"), std::nullopt);
  Write(dir + "/frames.csv.zst", {"a"});
  EXPECT_EQ(FindTextFile(dir, "frames.csv"), dir + "/frames.csv.zst");
  Write(dir + "/frames.csv", {"a"});
  EXPECT_THAT(
      [&] { FindTextFile(dir, "frames.csv"); },
      ::testing::ThrowsMessage<ConfigError>(HasSubstr("holds both frames.csv and frames.csv.zst")));
}

TEST(AtomicFileWriterTest, AnUncommittedWriterLeavesTheTargetAsItWas) {
  const std::string path = WriteTestFile("kept.csv", "old\n");
  {
    AtomicFileWriter writer(path);
    writer.Write("new\n");
  }
  EXPECT_EQ(ReadFileBytes(path), "old\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

}  // namespace
}  // namespace markerbench
