#include "trackers/circle/clipped_noise.h"

#include <algorithm>
#include <cmath>

namespace markerbench {

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
