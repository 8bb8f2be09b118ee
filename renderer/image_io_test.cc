// Image files are replaced atomically: no temporary is left, on success or on failure; a float
// image is written the same way each time.
#include "renderer/image_io.h"

#include <OpenImageIO/imageio.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <vector>

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

// The same frame gives the same bytes: no time of writing in an EXR's header.
TEST(ImageIo, AFloatImageCarriesNoTimeOfWriting) {
  ImageF image(4, 3, 3);
  for (size_t i = 0; i < image.data.size(); ++i) image.data[i] = 0.01f * static_cast<float>(i);
  const std::string path = WriteTestFile("linear.exr", "");
  WriteImageFloat(path, image);
  const std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
  ASSERT_TRUE(in) << OIIO::geterror();
  EXPECT_EQ(in->spec().find_attribute("DateTime"), nullptr)
      << in->spec().get_string_attribute("DateTime");
  // And the pixels as written (interleaved in the file, planar in ImageF).
  std::vector<float> read(image.data.size());
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, read.data()));
  for (int c = 0; c < 3; ++c) {
    for (size_t i = 0; i < image.plane_size(); ++i) {
      EXPECT_EQ(read[i * 3 + c], image.plane(c)[i]) << c << " " << i;
    }
  }
}

}  // namespace
}  // namespace markerbench
