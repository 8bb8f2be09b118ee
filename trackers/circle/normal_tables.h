// The normal distribution's functions tabulated for the photometric fits' inner loops
// (clipped_noise.h, blurred_ellipse.h): each by cubic Hermite interpolation from its values
// and derivatives at nodes evenly spaced over [-kEnd, kEnd], and in closed form beyond.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "trackers/circle/avx2_lanes.h"

namespace markerbench {

// The cubic Hermite basis at z for nodes `per_unit` to the unit from -end: the node below z
// and the weights of the values and slopes at it and at the next.
struct HermiteWeights {
  int node;
  double value0, slope0, value1, slope1;

  HermiteWeights(double z, double end, int per_unit, int nodes) {
    const double x = (z + end) * per_unit;
    node = std::min(static_cast<int>(x), nodes - 2);
    const double t = x - node, t2 = t * t, t3 = t2 * t, step = 1.0 / per_unit;
    value0 = 2.0 * t3 - 3.0 * t2 + 1.0;
    slope0 = (t3 - 2.0 * t2 + t) * step;
    value1 = 1.0 - value0;
    slope1 = (t3 - t2) * step;
  }

  // The interpolant from a table of a row per node, its values in column `value` and its
  // slopes in column `slope`.
  template <size_t N, size_t M>
  double Of(const std::array<std::array<double, M>, N>& rows, int value, int slope) const {
    return value0 * rows[node][value] + slope0 * rows[node][slope] +
           value1 * rows[node + 1][value] + slope1 * rows[node + 1][slope];
  }
};

// -log Q(z) and the inverse Mills ratio λ(z) = φ(z)/Q(z), with Q = 1 - Φ the normal tail
// ((-log Q)' = λ, λ' = λ (λ - z)), nodes 1/16 apart: below -kEnd 0, above kEnd the asymptotic
// series of Q; within 1e-6 of both, relative where they exceed 1 (tested).
class NormalTailTable {
 public:
  static constexpr double kEnd = 9.0;
  static constexpr int kPerUnit = 16;
  static constexpr int kNodes = 2 * static_cast<int>(kEnd) * kPerUnit + 1;

  struct Values {
    double minus_log_tail;  // -log Q(z)
    double mills;           // λ(z)
    double mills_excess;    // λ(z) - z
  };

  NormalTailTable();

  Values At(double z) const {
    if (!(z > -kEnd)) return {0.0, 0.0, -z};
    if (!(z < kEnd)) {
      // Q(z) = φ(z) S/z with S = 1 - u + 3u² - 15u³ + 105u⁴ - 945u⁵ + ..., u = 1/z².
      const double u = 1.0 / (z * z);
      const double one_minus_s = u * (1.0 - u * (3.0 - u * (15.0 - u * (105.0 - 945.0 * u))));
      const double s = 1.0 - one_minus_s;
      return {0.5 * z * z + std::log(z) + kHalfLogTwoPi - std::log(s), z / s, z * one_minus_s / s};
    }
    const HermiteWeights at(z, kEnd, kPerUnit, kNodes);
    const double mills = at.Of(rows_, kMills, kMillsSlope);
    return {at.Of(rows_, kMinusLogTail, kMills), mills, mills - z};
  }

 private:
  static constexpr double kHalfLogTwoPi = 0.91893853320467274178;
  // Per node -log Q, λ and λ' = λ (λ - z), a row each (NormalCdfTable's layout).
  static constexpr int kMinusLogTail = 0, kMills = 1, kMillsSlope = 2;
  std::array<std::array<double, 3>, kNodes> rows_{};
};
extern const NormalTailTable kNormalTailTable;

// Φ(z) and φ(z) (Φ' = φ, φ' = -z φ), nodes 1/64 apart: beyond kEnd 0 or 1 and 0 (φ(9) is
// 1e-18); within 2e-10 of both (the cubic Hermite error h^4/384 max |f''''|, with
// max |φ''''| = 3 φ(0); tested).
class NormalCdfTable {
 public:
  static constexpr double kEnd = 9.0;
  static constexpr int kPerUnit = 64;
  static constexpr int kNodes = 2 * static_cast<int>(kEnd) * kPerUnit + 1;

  struct Values {
    double cdf;      // Φ(z)
    double density;  // φ(z)
  };

  NormalCdfTable();

  Values At(double z) const {
    if (!(z > -kEnd)) return {0.0, 0.0};
    if (!(z < kEnd)) return {1.0, 0.0};
    const HermiteWeights at(z, kEnd, kPerUnit, kNodes);
    return {at.Of(rows_, kCdf, kDensity), at.Of(rows_, kDensity, kDensitySlope)};
  }

  // Φ(z) alone, as At's.
  double Cdf(double z) const {
    if (!(z > -kEnd)) return 0.0;
    if (!(z < kEnd)) return 1.0;
    return HermiteWeights(z, kEnd, kPerUnit, kNodes).Of(rows_, kCdf, kDensity);
  }

#if defined(__x86_64__)
  // At and Cdf of the four z in the lanes of an AVX2 vector (kCpuHasAvx2 only), each lane the
  // same operations in the same order as theirs, so the same bits (tested).
  struct Lanes {
    __m256d cdf, density;
  };
  MARKERBENCH_AVX2 Lanes AtLanes(__m256d z) const;
  MARKERBENCH_AVX2 __m256d CdfLanes(__m256d z) const;
#endif

 private:
  // Per node Φ, φ and φ' = -z φ, a row of 32 bytes (the fourth unused), so that the lanes read a
  // node's row whole and in one cache line: against a gather per value (six a lookup), full
  // detection at blur σ 8 took 0.91× the time (results/speed.md).
  static constexpr int kCdf = 0, kDensity = 1, kDensitySlope = 2;
  alignas(32) std::array<std::array<double, 4>, kNodes> rows_{};
};
extern const NormalCdfTable kNormalCdfTable;

}  // namespace markerbench
