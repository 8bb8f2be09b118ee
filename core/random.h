// Deterministic, portable randomness (architecture.md, "Randomness"). Every draw comes from
// an Rng seeded by SeedFor(scenario seed, sweep cell, trial, purpose): no global engines, no
// time seeds, and no std:: distributions (their output differs between standard libraries).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

namespace markerbench {

enum class SeedPurpose : uint64_t { kPose = 1, kNoise = 2, kTracker = 3, kMotion = 4 };

// Mixes the four coordinates with SplitMix64 (Steele, Lea and Flood 2014).
uint64_t SeedFor(uint64_t scenario_seed, uint64_t cell, uint64_t trial, SeedPurpose purpose);

// xoshiro256** (Blackman and Vigna 2018) with a Ziggurat normal sampler (Marsaglia and Tsang
// 2000, 256 blocks, with Doornik's 2005 independent block and position bits).
class Rng {
 public:
  explicit Rng(uint64_t seed);

  uint64_t NextU64() { return Next(state_); }
  // Uniform in [0, 1).
  double Uniform() { return static_cast<double>(NextU64() >> 11) * 0x1.0p-53; }
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  // Standard normal.
  double Gaussian();
  // n standard normals times `scale`, in single precision: each 64-bit draw feeds two
  // Ziggurat attempts (8 bits of block, 24 bits of position each). For sensor noise.
  void FillGaussian(float scale, size_t n, float* out);

 private:
  // One xoshiro256** step on `state` (kept in locals by the bulk sampler).
  static uint64_t Next(std::array<uint64_t, 4>& state) {
    const uint64_t result = RotateLeft(state[1] * 5, 7) * 9;
    const uint64_t t = state[1] << 17;
    state[2] ^= state[0];
    state[3] ^= state[1];
    state[1] ^= state[2];
    state[0] ^= state[3];
    state[2] ^= t;
    state[3] = RotateLeft(state[3], 45);
    return result;
  }
  static uint64_t RotateLeft(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

  // The rare Ziggurat branch: block i at position u in (-1, 1) was not inside the box.
  double GaussianSlowPath(int i, double u);
  double GaussianTail(bool negative);

  std::array<uint64_t, 4> state_;
};

}  // namespace markerbench
