// Image files are replaced atomically: no temporary is left, on success or on failure.
#include "renderer/image_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "core/test_files.h"

namespace markerbench {
namespace {

using ::testing::HasSubstr;

Image8 Flat(uint8_t value) {
  Image8 image;
  image.width = 4;
  image.height = 3;
  image.channels = 1;
  image.pixels.assign(12, value);
  return image;
}

TEST(ImageIo, WritingReplacesTheFileAndLeavesNoTemporary) {
  const std::string path = WriteTestFile("flat.png", "an older file");
  WriteImage(path, Flat(7), 300.0);
  EXPECT_EQ(ReadImage(path).pixels, Flat(7).pixels);
  WriteImage(path, Flat(200));
  EXPECT_EQ(ReadImage(path).pixels, Flat(200).pixels);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  for (const auto& entry : std::filesystem::directory_iterator(folder)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST(ImageIo, AFailedWriteNamesThePathAndLeavesNothing) {
  const std::string path = WriteTestFile("x.png", "") + ".d/missing/frame.png";
  try {
    WriteImage(path, Flat(1));
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr(path + ": cannot write"));
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp.png"));
}

}  // namespace
}  // namespace markerbench
