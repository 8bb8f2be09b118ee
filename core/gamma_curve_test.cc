#include "core/gamma_curve.h"

#include <gtest/gtest.h>

#include <cstdlib>

namespace markerbench {
namespace {

Image8 EveryValue() {
  Image8 image;
  image.width = 256;
  for (int v = 0; v < 256; ++v) image.pixels.push_back(static_cast<uint8_t>(v));
  return image;
}

TEST(GammaCurve, EncodingAndLinearizingRoundTripToALevel) {
  for (const double gamma : {1.8, 2.2, 2.4}) {
    Image8 image = EveryValue();
    ApplyGammaCurve(1.0 / gamma, &image);
    ApplyGammaCurve(gamma, &image);
    for (int v = 0; v < 256; ++v) {
      EXPECT_LE(std::abs(image.pixels[v] - v), 1) << "gamma " << gamma << ", value " << v;
    }
  }
}

TEST(GammaCurve, KeepsBlackAndWhiteAndBendsTheMiddle) {
  Image8 image = EveryValue();
  ApplyGammaCurve(2.2, &image);
  EXPECT_EQ(image.pixels[0], 0);
  EXPECT_EQ(image.pixels[255], 255);
  EXPECT_EQ(image.pixels[128], 56);  // 255 (128/255)^2.2 = 55.98
  Image8 same = EveryValue();
  ApplyGammaCurve(1.0, &same);
  EXPECT_EQ(same.pixels, EveryValue().pixels);
}

// A copy taken through the curve; the frame itself is left as it was.
TEST(GammaCurve, LinearizedIsACopyThroughTheCurve) {
  Image8 encoded = EveryValue();
  ApplyGammaCurve(1.0 / 2.2, &encoded);
  const Image8 before = encoded;
  const Image8 linear = Linearized(encoded, 2.2);
  EXPECT_EQ(encoded.pixels, before.pixels);
  Image8 expected = encoded;
  ApplyGammaCurve(2.2, &expected);
  EXPECT_EQ(linear.pixels, expected.pixels);
  EXPECT_NE(linear.pixels, encoded.pixels);
}

}  // namespace
}  // namespace markerbench
