// Bilinear interpolation of a grey 8-bit image between pixel centres (pixel (x, y) is the
// integer point (x, y); architecture.md), shared by the trackers that read codes by sampling.
// Inline: the circle tracker's alignment reads about 11,000 samples a call (results/speed.md).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

namespace markerbench {

// The level in one channel of an image of `channels` interleaved channels at p; p is clamped
// into the image. NaN where p has a NaN coordinate.
inline double BilinearSample(const uint8_t* pixels,
                             int width,
                             int height,
                             int channels,
                             int channel,
                             const Eigen::Vector2d& p) {
  // std::clamp passes NaN through, and a NaN cast to int is undefined.
  if (std::isnan(p.x()) || std::isnan(p.y())) return std::numeric_limits<double>::quiet_NaN();
  const double x = std::clamp(p.x(), 0.0, width - 1.001);
  const double y = std::clamp(p.y(), 0.0, height - 1.001);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const double fx = x - x0, fy = y - y0;
  const uint8_t* row = pixels + (static_cast<size_t>(y0) * width + x0) * channels + channel;
  const int below = width * channels;
  return (1 - fy) * ((1 - fx) * row[0] + fx * row[channels]) +
         fy * ((1 - fx) * row[below] + fx * row[below + channels]);
}

// The same in a grey image.
inline double BilinearSample(const uint8_t* grey, int width, int height, const Eigen::Vector2d& p) {
  return BilinearSample(grey, width, height, 1, 0, p);
}

}  // namespace markerbench
