// A grey 8-bit view of an observation's image: the image itself when it is grey, else its
// Rec. 601 luma (as cv::cvtColor RGB2GRAY).
#pragma once

#include <cstdint>
#include <vector>

#include "core/image.h"

namespace markerbench {

class GreyImage {
 public:
  explicit GreyImage(const Image8& image);
  int width() const { return width_; }
  int height() const { return height_; }
  // Row-major, stride = width.
  uint8_t* data() { return data_; }

 private:
  int width_;
  int height_;
  std::vector<uint8_t> converted_;
  uint8_t* data_;
};

}  // namespace markerbench
