#include "trackers/artkplus/pattern_reader.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "trackers/artkplus/homography.h"
#include "trackers/bilinear_sample.h"

namespace markerbench {
namespace {

// The pixel at integer coordinates `round` gives for p, clamped to the image (as a double
// before the cast: a point far off the image, or not a number, never overflows an int).
template <typename Round>
double PixelAt(const uint8_t* grey, int width, int height, const Eigen::Vector2d& p, Round round) {
  const auto clamped = [](double rounded, int size) {
    return rounded > 0.0 ? static_cast<int>(std::min(rounded, size - 1.0)) : 0;
  };
  const int x = clamped(round(p.x()), width);
  const int y = clamped(round(p.y()), height);
  return grey[static_cast<size_t>(y) * width + x];
}

}  // namespace

std::optional<PatternRead> ReadPattern(const uint8_t* grey,
                                       int width,
                                       int height,
                                       const std::array<Eigen::Vector2d, 4>& quad_px,
                                       int border_cells,
                                       ArtkPlusIdMode mode,
                                       const Camera& camera,
                                       const PatternReadOptions& options) {
  const bool distorted = camera.HasDistortion() && !options.truncated_samples;
  std::array<Eigen::Vector2d, 4> ideal;
  for (size_t i = 0; i < 4; ++i) {
    ideal[i] = distorted ? camera.IdealFromImg(quad_px[i]) : quad_px[i];
  }
  const Eigen::Matrix3d H =
      HomographyDlt({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {ideal.begin(), ideal.end()});
  const double cells = 6 + 2 * border_cells;
  const auto to_px = [&](const Eigen::Vector2d& unit) -> Eigen::Vector2d {
    const Eigen::Vector2d p = (H * unit.homogeneous()).hnormalized();
    return distorted ? camera.ImgFromIdeal(p) : p;
  };
  const int n = options.truncated_samples ? 1 : options.samples_per_side;
  std::array<double, kArtkPlusWordBits> level{};
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          const double du = 0.75 * ((j + 0.5) / n - 0.5), dv = 0.75 * ((i + 0.5) / n - 0.5);
          const Eigen::Vector2d p =
              to_px({(border_cells + c + 0.5 + du) / cells, (border_cells + r + 0.5 + dv) / cells});
          if (options.truncated_samples) {
            sum += PixelAt(grey, width, height, p, [](double v) { return std::trunc(v); });
          } else if (n == 1) {
            sum += PixelAt(grey, width, height, p, [](double v) { return std::round(v); });
          } else {
            sum += BilinearSample(grey, width, height, p);
          }
        }
      }
      level[static_cast<size_t>(6 * r + c)] = sum / (n * n);
    }
  }
  const auto [lo, hi] = std::minmax_element(level.begin(), level.end());
  // The mean level along the square `inset` cells inside the marker's outer edge (negative:
  // outside it), 8 bilinear samples a side.
  const auto ring_level = [&](double inset) {
    const double t = inset / cells;
    const std::array<Eigen::Vector2d, 4> corner = {
        Eigen::Vector2d(t, t), {1 - t, t}, {1 - t, 1 - t}, {t, 1 - t}};
    double sum = 0.0;
    for (size_t side = 0; side < 4; ++side) {
      for (int k = 0; k < 8; ++k) {
        const Eigen::Vector2d unit =
            corner[side] + (k + 0.5) / 8.0 * (corner[(side + 1) % 4] - corner[side]);
        sum += BilinearSample(grey, width, height, to_px(unit));
      }
    }
    return sum / 32.0;
  };
  if (options.min_code_contrast > 0.0) {
    const double ink = ring_level(0.5 * border_cells), paper = ring_level(-0.5);
    const double code_contrast = (*hi - *lo) / (paper - ink);
    if (!(paper > ink && code_contrast >= options.min_code_contrast &&
          code_contrast <= 1.0 / options.min_code_contrast)) {
      return std::nullopt;
    }
  }
  const double white_above =
      options.bit_threshold >= 0.0 ? options.bit_threshold : 0.5 * (*lo + *hi);
  uint64_t word = 0;
  for (size_t k = 0; k < level.size(); ++k) {
    if (level[k] > white_above) word |= 1ULL << (35 - k);  // a set bit is white
  }
  // Reading with corner j as top-left gives the word read with corner j+1 turned a quarter
  // turn clockwise; so turning the word read from corner 0 k times reads it from corner -k.
  std::optional<PatternRead> best;
  bool tie = false;
  for (int k = 0; k < 4; ++k, word = ArtkPlusQuarterTurn(word)) {
    const std::optional<DecodedId> decoded = ArtkPlusDecode(mode, word);
    if (!decoded || decoded->corrected_bits > options.max_corrected_bits) continue;
    if (best && decoded->corrected_bits == best->corrected_bits) tie = true;
    if (best && decoded->corrected_bits >= best->corrected_bits) continue;
    tie = false;
    best = PatternRead{
        decoded->id,
        decoded->corrected_bits,
        1.0 - static_cast<double>(decoded->corrected_bits) / ArtkPlusMinimumDistance(mode),
        (4 - k) % 4,
        *lo,
        *hi};
  }
  if (tie) return std::nullopt;
  return best;
}

}  // namespace markerbench
