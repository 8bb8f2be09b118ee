#include "renderer/image_io.h"

#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <stdexcept>
#include <vector>

#include "core/camera_yaml.h"

namespace markerbench {
namespace {

// Writes a temporary file beside `path` (the same extension, so the same format) and renames
// it over `path`: a killed program never leaves half an image.
void Write(const std::string& path,
           const OIIO::ImageSpec& spec,
           OIIO::TypeDesc type,
           const void* data) {
  const std::string temporary = path + ".tmp" + std::filesystem::path(path).extension().string();
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw std::runtime_error(path + ": cannot write: " + OIIO::geterror());
  if (!out->open(temporary, spec) || !out->write_image(type, data) || !out->close()) {
    const std::string error = out->geterror();
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error(path + ": cannot write: " + error);
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) {
    const std::string message = error.message();
    std::filesystem::remove(temporary, error);
    throw std::runtime_error(path + ": cannot write: " + message);
  }
}

}  // namespace

void WriteImage(const std::string& path, const Image8& image, std::optional<double> dpi) {
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::UINT8);
  if (dpi) {
    spec.attribute("XResolution", static_cast<float>(*dpi));
    spec.attribute("YResolution", static_cast<float>(*dpi));
    spec.attribute("ResolutionUnit", "inch");
  }
  Write(path, spec, OIIO::TypeDesc::UINT8, image.pixels.data());
}

void WriteImageFloat(const std::string& path, const ImageF& image) {
  std::vector<float> interleaved(image.data.size());
  for (int c = 0; c < image.channels; ++c) {
    for (size_t i = 0; i < image.plane_size(); ++i) {
      interleaved[i * image.channels + c] = image.plane(c)[i];
    }
  }
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  // No time in the header: OpenImageIO's EXR writer stamps the time of writing (capDate) where
  // none is given, and the same frame rendered twice gave two files.
  spec.attribute("DateTime", "");
  Write(path, spec, OIIO::TypeDesc::FLOAT, interleaved.data());
}

Image8 ReadImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error(path + ": cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width < 1 || spec.height < 1 || spec.nchannels < 1 ||
      static_cast<int64_t>(spec.width) * spec.height > kMaxImagePixels) {
    throw std::runtime_error(path + ": cannot read image: its header says " +
                             std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                             " pixels; markerbench reads 1 to " + std::to_string(kMaxImagePixels) +
                             " pixels");
  }
  Image8 image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels >= 3 ? 3 : 1;
  image.pixels.resize(static_cast<size_t>(image.width) * image.height * image.channels);
  if (!in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::UINT8, image.pixels.data())) {
    throw std::runtime_error(path + ": cannot read image: " + in->geterror());
  }
  return image;
}

}  // namespace markerbench
