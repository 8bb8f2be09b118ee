// Bilinear interpolation of a grey 8-bit image between pixel centres (pixel (x, y) is the
// integer point (x, y); architecture.md), shared by the trackers that read codes by sampling.
#pragma once

#include <Eigen/Core>
#include <cstdint>

namespace markerbench {

// The grey level at p; p is clamped into the image. NaN where p has a NaN coordinate.
double BilinearSample(const uint8_t* grey, int width, int height, const Eigen::Vector2d& p);

// The same in one channel of an image of `channels` interleaved channels.
double BilinearSample(const uint8_t* pixels,
                      int width,
                      int height,
                      int channels,
                      int channel,
                      const Eigen::Vector2d& p);

}  // namespace markerbench
