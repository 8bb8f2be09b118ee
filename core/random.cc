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

constexpr int kBlocks = 256;
constexpr double kTailStart = 3.6541528853610088;  // r for 256 blocks (Marsaglia, Tsang 2000)
constexpr double kBlockArea = 4.92867323399e-3;    // v, the area of each block

struct ZigguratTables {
  double x[kBlocks + 1];
  double ratio[kBlocks];
  double density[kBlocks + 1];  // exp(-x²/2) at each block edge

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
    for (int i = 0; i <= kBlocks; ++i) density[i] = std::exp(-0.5 * x[i] * x[i]);
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
  // Accept under the density within the wedge between the block edges.
  const double x = u * z.x[i];
  const double y = z.density[i + 1] + Uniform() * (z.density[i] - z.density[i + 1]);
  if (y < std::exp(-0.5 * x * x)) return x;
  return std::nan("");  // rejected: draw again
}

void Rng::FillGaussian(float scale, size_t n, float* out) {
  struct FloatTables {
    float x[kBlocks];
    float ratio[kBlocks];
  };
  static const FloatTables f = [] {
    FloatTables t;
    for (int i = 0; i < kBlocks; ++i) {
      t.x[i] = static_cast<float>(Tables().x[i]);
      t.ratio[i] = static_cast<float>(Tables().ratio[i]);
    }
    return t;
  }();
  std::array<uint64_t, 4> state = state_;  // in registers; synced around the slow path
  size_t k = 0;
  while (k < n) {
    const uint64_t bits = Next(state);
    for (int half = 0; half < 2 && k < n; ++half) {
      const uint32_t h = static_cast<uint32_t>(bits >> (32 * half));
      const int i = static_cast<int>(h & (kBlocks - 1));
      // 24 bits → u in [-1, 1) on a grid of 2^-23.
      const float u = static_cast<float>(static_cast<int32_t>(h >> 8) - (1 << 23)) * 0x1.0p-23f;
      if (std::abs(u) < f.ratio[i]) {
        out[k++] = scale * u * f.x[i];
        continue;
      }
      state_ = state;
      const double x = GaussianSlowPath(i, u);
      state = state_;
      if (!std::isnan(x)) out[k++] = scale * static_cast<float>(x);
    }
  }
  state_ = state;
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
