// A power curve on 8-bit values: v -> round(255 (v/255)^exponent). A camera's encoding with gamma
// G is the exponent 1/G, and taking such a frame back to values linear in the light, G.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "core/image.h"

namespace markerbench {

// The gammas a camera's response may have, in the renderer (Degradations::gamma) and for the
// frames a tracker is given (`track --gamma`): beyond them an 8-bit frame keeps few levels.
constexpr double kMinGamma = 0.1, kMaxGamma = 10.0;
inline bool IsValidGamma(double gamma) { return gamma >= kMinGamma && gamma <= kMaxGamma; }

// Every pixel and channel of `image` through the curve; `exponent` > 0.
inline void ApplyGammaCurve(double exponent, Image8* image) {
  std::array<uint8_t, 256> curve;
  for (int v = 0; v < 256; ++v) {
    curve[v] = static_cast<uint8_t>(std::lround(255.0 * std::pow(v / 255.0, exponent)));
  }
  for (uint8_t& v : image->pixels) v = curve[v];
}

// `image` taken back to linear values from a camera's encoding with gamma G (the curve's
// exponent G): what a tracker told the camera's response sees.
inline Image8 Linearized(const Image8& image, double gamma) {
  Image8 linear = image;
  ApplyGammaCurve(gamma, &linear);
  return linear;
}

}  // namespace markerbench
