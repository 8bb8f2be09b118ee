// Image buffers. Image8 is what trackers see and files hold (interleaved, row-major);
// ImageF is the renderer's linear working buffer (planar float, one plane per channel).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace markerbench {

struct Image8 {
  int width = 0;
  int height = 0;
  int channels = 1;  // 1 (grey) or 3 (RGB)
  std::vector<uint8_t> pixels;

  uint8_t at(int x, int y, int c = 0) const {
    return pixels[(static_cast<size_t>(y) * width + x) * channels + c];
  }
};

struct ImageF {
  int width = 0;
  int height = 0;
  int channels = 1;
  std::vector<float> data;  // channels planes of width * height

  ImageF() = default;
  ImageF(int w, int h, int c)
      : width(w), height(h), channels(c), data(static_cast<size_t>(w) * h * c, 0.0f) {}
  size_t plane_size() const { return static_cast<size_t>(width) * height; }
  float* plane(int c) { return data.data() + c * plane_size(); }
  const float* plane(int c) const { return data.data() + c * plane_size(); }
  float at(int x, int y, int c = 0) const { return plane(c)[static_cast<size_t>(y) * width + x]; }
};

}  // namespace markerbench
