#include "trackers/runetag/ring_decoder.h"

#include <gtest/gtest.h>

#include <cmath>

namespace markerbench {
namespace {

// 400 small rings of 9 dots, 100 px apart: every dot has neighbours, so all 3600 are sampled,
// and the best conic (a small ring) holds 9 of them. The RANSAC stop then asks for about
// 2e11 iterations, which must be capped before it is made an int (fuzzing found the cast,
// UBSan's float-cast-overflow); the search ends, and no ring of the marker's decodes.
TEST(MatchRings, HundredsOfSmallRingsMatchNoMarker) {
  std::vector<ImagedDot> dots;
  for (int row = 0; row < 20; ++row) {
    for (int col = 0; col < 20; ++col) {
      for (int k = 0; k < 9; ++k) {
        ImagedDot dot;
        const double angle = 2.0 * M_PI * k / 9.0;
        dot.center_px = {50.0 + 100.0 * col + 8.0 * std::cos(angle),
                         50.0 + 100.0 * row + 8.0 * std::sin(angle)};
        dot.semi_major_px = dot.semi_minor_px = 1.2;
        dot.area_px = M_PI * 1.2 * 1.2;
        dots.push_back(dot);
      }
    }
  }
  DotImage image;
  image.smoothed = cv::Mat(2000, 2000, CV_8UC1, cv::Scalar(230));
  image.noise = 1.0;
  Camera camera;
  camera.width = camera.height = 2000;
  camera.fx = camera.fy = 2400.0;
  camera.cx = camera.cy = 999.5;
  RingDecoderOptions options;
  options.read_slot_levels = options.decode_missing_dots = true;  // runetag-improved's reading
  EXPECT_FALSE(MatchRings(dots, image, camera, 7, 8, options));   // scenarios/markers/runetag.yaml
}

}  // namespace
}  // namespace markerbench
