#include "core/random.h"

#include <cmath>

namespace markerbench {
namespace {

uint64_t SplitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

uint64_t RotateLeft(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

constexpr int kBlocks = 128;
constexpr double kTailStart = 3.442619855899;       // r for 128 blocks (Doornik 2005)
constexpr double kBlockArea = 9.91256303526217e-3;  // v, the area of each block

struct ZigguratTables {
  double x[kBlocks + 1];
  double ratio[kBlocks];

  ZigguratTables() {
    double f = std::exp(-0.5 * kTailStart * kTailStart);
    x[0] = kBlockArea / f;
    x[1] = kTailStart;
    x[kBlocks] = 0.0;
    for (int i = 2; i < kBlocks; ++i) {
      x[i] = std::sqrt(-2.0 * std::log(kBlockArea / x[i - 1] + f));
      f = std::exp(-0.5 * x[i] * x[i]);
    }
    for (int i = 0; i < kBlocks; ++i) ratio[i] = x[i + 1] / x[i];
  }
};

const ZigguratTables& Tables() {
  static const ZigguratTables tables;
  return tables;
}

}  // namespace

uint64_t SeedFor(uint64_t scenario_seed, uint64_t cell, uint64_t trial, SeedPurpose purpose) {
  uint64_t h = SplitMix64(scenario_seed);
  h = SplitMix64(h ^ cell);
  h = SplitMix64(h ^ trial);
  return SplitMix64(h ^ static_cast<uint64_t>(purpose));
}

Rng::Rng(uint64_t seed) {
  uint64_t s = seed;
  for (uint64_t& word : state_) {
    s = SplitMix64(s);
    word = s;
  }
}

uint64_t Rng::NextU64() {
  const uint64_t result = RotateLeft(state_[1] * 5, 7) * 9;
  const uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = RotateLeft(state_[3], 45);
  return result;
}

double Rng::Gaussian() {
  const ZigguratTables& z = Tables();
  for (;;) {
    const uint64_t bits = NextU64();
    const int i = static_cast<int>(bits & (kBlocks - 1));
    const double u = 2.0 * (static_cast<double>(bits >> 11) * 0x1.0p-53) - 1.0;
    if (std::abs(u) < z.ratio[i]) return u * z.x[i];
    const double x = GaussianSlowPath(i, u);
    if (!std::isnan(x)) return x;
  }
}

double Rng::GaussianSlowPath(int i, double u) {
  const ZigguratTables& z = Tables();
  if (i == 0) return GaussianTail(u < 0.0);
  const double x = u * z.x[i];
  const double f0 = std::exp(-0.5 * (z.x[i] * z.x[i] - x * x));
  const double f1 = std::exp(-0.5 * (z.x[i + 1] * z.x[i + 1] - x * x));
  if (f1 + Uniform() * (f0 - f1) < 1.0) return x;
  return std::nan("");  // rejected: draw again
}

void Rng::FillGaussian(float scale, size_t n, float* out) {
  const ZigguratTables& z = Tables();
  float x_f[kBlocks], ratio_f[kBlocks];
  for (int i = 0; i < kBlocks; ++i) {
    x_f[i] = static_cast<float>(z.x[i]);
    ratio_f[i] = static_cast<float>(z.ratio[i]);
  }
  size_t k = 0;
  while (k < n) {
    const uint64_t bits = NextU64();
    for (int half = 0; half < 2 && k < n; ++half) {
      const uint32_t h = static_cast<uint32_t>(bits >> (32 * half));
      const int i = static_cast<int>(h & (kBlocks - 1));
      // 24 bits → u in [-1, 1) on a grid of 2^-23.
      const float u = static_cast<float>(static_cast<int32_t>(h >> 8) - (1 << 23)) * 0x1.0p-23f;
      if (std::abs(u) < ratio_f[i]) {
        out[k++] = scale * u * x_f[i];
        continue;
      }
      const double x = GaussianSlowPath(i, u);
      if (!std::isnan(x)) out[k++] = scale * static_cast<float>(x);
    }
  }
}

double Rng::GaussianTail(bool negative) {
  double x, y;
  do {
    x = std::log(1.0 - Uniform()) / kTailStart;  // 1 - U is in (0, 1]
    y = std::log(1.0 - Uniform());
  } while (-2.0 * y < x * x);
  return negative ? x - kTailStart : kTailStart - x;
}

}  // namespace markerbench
