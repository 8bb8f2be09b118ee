#include "trackers/circle/blurred_disk_profile.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace markerbench {
namespace {

constexpr double kMinS = 0.5, kMaxS = 40.0;
constexpr double kMinT = 1.0 / kMaxS, kMaxT = 1.0 / kMinS;
constexpr int kTSteps = 160;
constexpr double kMaxZ = 7.0, kZStep = 0.05;
constexpr int kZSteps = static_cast<int>(2 * kMaxZ / kZStep);

// e^{-y} I₀(y), y >= 0 (Abramowitz and Stegun 9.8.1-9.8.2).
double ScaledBesselI0(double y) {
  if (y < 3.75) {
    const double t = (y / 3.75) * (y / 3.75);
    const double i0 =
        1.0 +
        t * (3.5156229 +
             t * (3.0899424 + t * (1.2067492 + t * (0.2659732 + t * (0.0360768 + t * 0.0045813)))));
    return i0 * std::exp(-y);
  }
  const double t = 3.75 / y;
  return (0.39894228 +
          t * (0.01328592 +
               t * (0.00225319 +
                    t * (-0.00157565 +
                         t * (0.00916281 +
                              t * (-0.02057706 +
                                   t * (0.02635537 + t * (-0.01647633 + t * 0.00392377)))))))) /
         std::sqrt(y);
}

// G(s, z) = ∫₀^s u exp(-(u - x)²/2) e^{-ux} I₀(ux) du with x = s - z (Simpson's rule).
double Integrate(double s, double z) {
  const double x = std::max(0.0, s - z);
  const double lo = std::max(0.0, x - 9.0), hi = std::min(s, x + 9.0);
  if (hi <= lo) return x > s ? 0.0 : 1.0;
  const int n = 120;
  const double h = (hi - lo) / n;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double u = lo + k * h;
    const double f = u * std::exp(-0.5 * (u - x) * (u - x)) * ScaledBesselI0(u * x);
    sum += f * (k == 0 || k == n ? 1.0 : (k % 2 ? 4.0 : 2.0));
  }
  return std::clamp(sum * h / 3.0, 0.0, 1.0);
}

struct Table {
  std::vector<double> values;  // (kTSteps + 1) x (kZSteps + 1), t-major
  Table() : values(static_cast<size_t>(kTSteps + 1) * (kZSteps + 1)) {
    for (int i = 0; i <= kTSteps; ++i) {
      const double s = 1.0 / (kMinT + (kMaxT - kMinT) * i / kTSteps);
      for (int j = 0; j <= kZSteps; ++j)
        values[i * (kZSteps + 1) + j] = Integrate(s, -kMaxZ + j * kZStep);
    }
  }
  const double* row(int i) const { return values.data() + static_cast<size_t>(i) * (kZSteps + 1); }
};

const Table& TheTable() {
  static const Table table;
  return table;
}

}  // namespace

BlurredDiskProfile::BlurredDiskProfile(double s) {
  const Table& table = TheTable();
  const double t = 1.0 / (s > kMinS ? std::min(s, kMaxS) : kMinS);  // NaN: the smallest
  const double ti = (t - kMinT) / (kMaxT - kMinT) * kTSteps;
  const int i = std::min(static_cast<int>(ti), kTSteps - 1);
  row0_ = table.row(i);
  row1_ = table.row(i + 1);
  weight_ = ti - i;
  // dt/ds = -1/s² (zero where s is clamped).
  if (s > kMinS && s < kMaxS) d_weight_ds_ = kTSteps / (kMaxT - kMinT) * (-t * t);
}

ProfileValue BlurredDiskProfile::At(double z) const {
  ProfileValue out;
  if (z <= -kMaxZ) return out;
  if (z >= kMaxZ) {
    out.value = 1.0;
    return out;
  }
  const double zj = (z + kMaxZ) / kZStep;
  const int j = std::min(static_cast<int>(zj), kZSteps - 1);
  const double fz = zj - j, ft = weight_;
  const double g00 = row0_[j], g01 = row0_[j + 1], g10 = row1_[j], g11 = row1_[j + 1];
  out.value = (1 - ft) * ((1 - fz) * g00 + fz * g01) + ft * ((1 - fz) * g10 + fz * g11);
  out.d_dz = ((1 - ft) * (g01 - g00) + ft * (g11 - g10)) / kZStep;
  out.d_ds = ((1 - fz) * (g10 - g00) + fz * (g11 - g01)) * d_weight_ds_;
  return out;
}

}  // namespace markerbench
