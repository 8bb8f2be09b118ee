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

void FitOffsetsAndGains(int channels,
                        Eigen::VectorXd* levels,
                        std::vector<ModelledPixel>* modelled) {
  for (int c = 0; c < channels; ++c) {
    double n = 0.0, sum_x = 0.0, sum_y = 0.0, sum_xx = 0.0, sum_xy = 0.0;
    for (size_t i = c; i < modelled->size(); i += channels) {
      const double x = (*modelled)[i].mean, y = (*modelled)[i].residual + x;
      if (!(x > 0.1 && x < 0.9)) continue;
      n += 1.0;
      sum_x += x;
      sum_y += y;
      sum_xx += x * x;
      sum_xy += x * y;
    }
    const double spread = n * sum_xx - sum_x * sum_x;  // n² times the variance of x
    if (!(spread > 0.0)) continue;
    const double gain = (n * sum_xy - sum_x * sum_y) / spread;
    if (!(gain > 0.0 && std::isfinite(gain))) continue;
    (*levels)[2 * c] = (sum_y - gain * sum_x) / n;
    (*levels)[2 * c + 1] = gain;
  }
  for (size_t i = 0; i < modelled->size(); ++i) {
    const int c = static_cast<int>(i % channels);
    ModelledPixel& pixel = (*modelled)[i];
    const double value = pixel.residual + pixel.mean;
    pixel.mean = (*levels)[2 * c] + (*levels)[2 * c + 1] * pixel.mean;
    pixel.residual = value - pixel.mean;
  }
}

}  // namespace markerbench
