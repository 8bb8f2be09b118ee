#include "trackers/circle/clipped_noise.h"

#include <algorithm>
#include <cmath>

#include "trackers/circle/blurred_design.h"

namespace markerbench {
NormalTailTable::NormalTailTable() {
  for (int i = 0; i < kNodes; ++i) {
    const double z = -kEnd + static_cast<double>(i) / kPerUnit;
    const double tail = 0.5 * std::erfc(z / std::sqrt(2.0));
    minus_log_tail_[i] = -std::log(tail);
    mills_[i] = NormalDensity(z) / tail;
    mills_slope_[i] = mills_[i] * (mills_[i] - z);
  }
}

const NormalTailTable kNormalTailTable;

double ModelNoiseSigma(double noise_sigma) {
  return std::max(noise_sigma, 1.0 / (255.0 * std::sqrt(12.0)));
}

std::optional<double> MidRangeNoise(const std::vector<ModelledPixel>& modelled) {
  double sum = 0.0;
  int count = 0;
  for (const ModelledPixel& pixel : modelled) {
    if (pixel.mean < 0.2 || pixel.mean > 0.8) continue;
    sum += pixel.residual * pixel.residual;
    ++count;
  }
  if (count < 50) return std::nullopt;
  return std::sqrt(sum / count);
}

}  // namespace markerbench
