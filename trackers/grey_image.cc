#include "trackers/grey_image.h"

#include <opencv2/imgproc.hpp>

namespace markerbench {

GreyImage::GreyImage(const Image8& image) : width_(image.width), height_(image.height) {
  if (image.channels == 1) {
    // Detectors read the buffer only; the const_cast lets C APIs take it without a copy.
    data_ = const_cast<uint8_t*>(image.pixels.data());
    return;
  }
  converted_.resize(static_cast<size_t>(width_) * height_);
  const cv::Mat rgb(height_, width_, CV_8UC3, const_cast<uint8_t*>(image.pixels.data()));
  cv::Mat grey(height_, width_, CV_8UC1, converted_.data());
  cv::cvtColor(rgb, grey, cv::COLOR_RGB2GRAY);
  data_ = converted_.data();
}

}  // namespace markerbench
