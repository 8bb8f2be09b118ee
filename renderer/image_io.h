// Image files through OpenImageIO: 8-bit PNG (or any format OIIO knows by extension), and
// float images (EXR) for linear output.
#pragma once

#include <optional>
#include <string>

#include "core/image.h"

namespace markerbench {

// Both writers replace the file atomically (a temporary beside it, renamed), so a killed
// program never leaves half an image, and throw std::runtime_error naming the path.
// Writes an 8-bit image; dpi, when given, is stored as the file's resolution.
void WriteImage(const std::string& path, const Image8& image, std::optional<double> dpi = {});
// Writes a float image (e.g. .exr), channels interleaved on disk.
void WriteImageFloat(const std::string& path, const ImageF& image);
// Reads an 8-bit image (1 or 3 channels; alpha is dropped, other types are converted).
Image8 ReadImage(const std::string& path);

}  // namespace markerbench
