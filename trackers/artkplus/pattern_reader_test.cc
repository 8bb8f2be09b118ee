#include "trackers/artkplus/pattern_reader.h"

#include <gtest/gtest.h>

#include <vector>

namespace markerbench {
namespace {

constexpr int kSize = 160, kCellPx = 8, kOrigin = 32, kBorderCells = 3;
constexpr uint8_t kPaper = 230, kInk = 20;

// A BCH marker drawn axis-aligned: 12 cells of 8 px from pixel 32, the border at
// `border_level`, white cells at `white` and black ones at `black`.
std::vector<uint8_t> DrawMarker(int id, uint8_t border_level, uint8_t white, uint8_t black) {
  std::vector<uint8_t> image(kSize * kSize, kPaper);
  const uint64_t word = ArtkPlusEncode(ArtkPlusIdMode::kBch, id);
  for (int y = 0; y < 12 * kCellPx; ++y) {
    for (int x = 0; x < 12 * kCellPx; ++x) {
      const int r = y / kCellPx - kBorderCells, c = x / kCellPx - kBorderCells;
      uint8_t level = border_level;
      if (r >= 0 && r < 6 && c >= 0 && c < 6) {
        level = (word >> (35 - (6 * r + c))) & 1 ? white : black;
      }
      image[(kOrigin + y) * kSize + kOrigin + x] = level;
    }
  }
  return image;
}

std::optional<PatternRead> Read(const std::vector<uint8_t>& image, double min_code_contrast) {
  const double lo = kOrigin - 0.5, hi = kOrigin + 12 * kCellPx - 0.5;
  Camera camera;
  camera.width = camera.height = kSize;
  PatternReadOptions options;
  options.truncated_samples = false;
  options.samples_per_side = 3;
  options.max_corrected_bits = 2;
  options.min_code_contrast = min_code_contrast;
  return ReadPattern(image.data(),
                     kSize,
                     kSize,
                     {Eigen::Vector2d(lo, lo), {hi, lo}, {hi, hi}, {lo, hi}},
                     kBorderCells,
                     ArtkPlusIdMode::kBch,
                     camera,
                     options);
}

TEST(PatternReader, AMarkerAtFullContrastDecodes) {
  const std::optional<PatternRead> read = Read(DrawMarker(77, kInk, kPaper, kInk), 0.3);
  ASSERT_TRUE(read.has_value());
  EXPECT_EQ(read->id, 77);
  EXPECT_EQ(read->corrected_bits, 0);
  EXPECT_EQ(read->top_left, 0);
}

// A quad whose border is not darker than the paper around it is not a marker, whatever its
// interior decodes to.
TEST(PatternReader, CodeContrastRejectsAQuadWithoutADarkBorder) {
  const std::vector<uint8_t> no_border = DrawMarker(77, kPaper, kPaper, kInk);
  EXPECT_TRUE(Read(no_border, 0.0).has_value());
  EXPECT_FALSE(Read(no_border, 0.3).has_value());
}

// Cells whose range is a fifth of the border's contrast (as heavy blur leaves them) are not
// read; at a half they are.
TEST(PatternReader, CodeContrastRejectsAFadedCode) {
  const std::vector<uint8_t> faded = DrawMarker(77, kInk, 145, 105);
  EXPECT_EQ(Read(faded, 0.0)->id, 77);
  EXPECT_FALSE(Read(faded, 0.3).has_value());
  EXPECT_EQ(Read(DrawMarker(77, kInk, 175, 75), 0.3)->id, 77);
}

}  // namespace
}  // namespace markerbench
