// A pixel's area as a blur: a pixel averages the image over its square, which adds a variance
// of 1/12 px² (a box one pixel wide) to the blur every edge in the image shows. A model that
// averages over each pixel itself takes the rest of the edges' σ.
#pragma once

#include <algorithm>
#include <cmath>

namespace markerbench {

// A pixel's variance along any direction (px², its side 1 px).
constexpr double kPixelAreaVariance = 1.0 / 12.0;

// The blur σ of a model that averages over each pixel from the σ of the image's edges, which
// holds the pixel's area too.
inline double BlurSigmaOfEdges(double edge_sigma_px) {
  return std::sqrt(std::max(0.0, edge_sigma_px * edge_sigma_px - kPixelAreaVariance));
}
// Its inverse: the σ of the edges of an image of blur σ.
inline double EdgeSigmaOfBlur(double blur_sigma_px) {
  return std::sqrt(blur_sigma_px * blur_sigma_px + kPixelAreaVariance);
}

}  // namespace markerbench
