#include "trackers/circle/blurred_disk_profile.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "trackers/circle/avx2_lanes.h"

namespace markerbench {
namespace {

constexpr double kMinS = 0.5;
constexpr double kMinT = 0.0, kMaxT = 1.0 / kMinS;  // t = 1/s; t = 0 a straight edge
constexpr int kTSteps = 160;
constexpr double kMaxZ = 7.0, kZStep = 0.05, kPerZStep = 1.0 / kZStep;
constexpr int kZSteps = static_cast<int>(2 * kMaxZ / kZStep);
constexpr size_t kRowSize = static_cast<size_t>(kZSteps) + 1;  // z values a table row
// What a NaN point gives (a fit's step gone astray): NaN, which the fit rejects, never a
// table index (a NaN cast to int is undefined; on x86 it read far outside the table).
constexpr double kNotANumber = std::numeric_limits<double>::quiet_NaN();

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

// G and its first and second integrals in z from -kMaxZ (cumulative trapezoids: their error,
// h²/12 times the integrand's derivative, is below 2e-4 and smooth in z).
struct Table {
  static constexpr size_t kSize = static_cast<size_t>(kTSteps + 1) * kRowSize;
  std::vector<double> values, first, second;  // (kTSteps + 1) x (kZSteps + 1), t-major
  Table() : values(kSize), first(kSize), second(kSize) {
    for (int i = 0; i <= kTSteps; ++i) {
      const double t = kMinT + (kMaxT - kMinT) * i / kTSteps;
      const size_t row = Row(i);
      for (int j = 0; j <= kZSteps; ++j) {
        const double z = -kMaxZ + j * kZStep;
        values[row + j] = t > 0.0 ? Integrate(1.0 / t, z) : 0.5 * std::erfc(-z / std::sqrt(2.0));
        if (j == 0) continue;
        first[row + j] =
            first[row + j - 1] + 0.5 * kZStep * (values[row + j - 1] + values[row + j]);
        second[row + j] =
            second[row + j - 1] + 0.5 * kZStep * (first[row + j - 1] + first[row + j]);
      }
    }
  }
  static size_t Row(int i) { return static_cast<size_t>(i) * kRowSize; }
};

const Table& TheTable() {
  static const Table table;
  return table;
}

}  // namespace

void PrepareBlurredDiskProfiles() { TheTable(); }

BlurredDiskProfile::BlurredDiskProfile(double s) {
  const Table& table = TheTable();
  const double t = 1.0 / (s > kMinS ? s : kMinS);  // NaN: the smallest s
  const double ti = (t - kMinT) / (kMaxT - kMinT) * kTSteps;
  const int i = std::min(static_cast<int>(ti), kTSteps - 1);
  values_ = table.values.data() + Table::Row(i);
  first_ = table.first.data() + Table::Row(i);
  second_ = table.second.data() + Table::Row(i);
  if (i == 0) {
    // Wider than the first row after the straight edge's (s > 80): that edge moved by t/2,
    // one row where interpolating two would cost more (a sharp image's disks are all here).
    shift_ = 0.5 * t;
    d_shift_ds_ = -0.5 * t * t;
    return;
  }
  weight_ = ti - i;
  // dt/ds = -1/s² (zero where s is clamped).
  if (s > kMinS) d_weight_ds_ = kTSteps / (kMaxT - kMinT) * (-t * t);
}

ProfileValue BlurredDiskProfile::At(double z) const {
  ProfileValue out;
  z -= shift_;
  if (std::isnan(z)) return {kNotANumber, kNotANumber, kNotANumber};
  if (z <= -kMaxZ) return out;
  if (z >= kMaxZ) {
    out.value = 1.0;
    return out;
  }
  const double zj = (z + kMaxZ) / kZStep;
  const int j = std::min(static_cast<int>(zj), kZSteps - 1);
  const double fz = zj - j, ft = weight_;
  const double* next = values_ + kRowSize;
  const double g00 = values_[j], g01 = values_[j + 1], g10 = next[j], g11 = next[j + 1];
  out.value = (1 - ft) * ((1 - fz) * g00 + fz * g01) + ft * ((1 - fz) * g10 + fz * g11);
  out.d_dz = ((1 - ft) * (g01 - g00) + ft * (g11 - g10)) / kZStep;
  out.d_ds = ((1 - fz) * (g10 - g00) + fz * (g11 - g01)) * d_weight_ds_ - out.d_dz * d_shift_ds_;
  return out;
}

BlurredDiskProfile::Integral BlurredDiskProfile::SecondIntegralAt(double x) const {
  Integral out;
  x -= shift_;
  if (std::isnan(x)) return {kNotANumber, kNotANumber, kNotANumber};
  if (x <= -kMaxZ) return out;
  // Each row's H at x: cubic Hermite from its values and slopes (the first integral) at the
  // nodes around x, and that cubic's derivative; beyond kMaxZ, G = 1.
  const double beyond = std::max(0.0, x - kMaxZ);
  const double xj = (std::min(x, kMaxZ) + kMaxZ) * kPerZStep;
  const int j = std::min(static_cast<int>(xj), kZSteps - 1);
  const double f = xj - j, f2 = f * f, f3 = f2 * f;
  const double value0 = 2.0 * f3 - 3.0 * f2 + 1.0, value1 = 1.0 - value0;
  const double slope0 = (f3 - 2.0 * f2 + f) * kZStep, slope1 = (f3 - f2) * kZStep;
  const double d_value0 = (6.0 * f2 - 6.0 * f) * kPerZStep, d_value1 = -d_value0;
  const double d_slope0 = 3.0 * f2 - 4.0 * f + 1.0, d_slope1 = 3.0 * f2 - 2.0 * f;
  const auto row_integral = [&](const double* first, const double* second) {
    const double end_slope = first[kZSteps];
    return std::pair<double, double>{
        value0 * second[j] + slope0 * first[j] + value1 * second[j + 1] + slope1 * first[j + 1] +
            beyond * end_slope + 0.5 * beyond * beyond,
        d_value0 * second[j] + d_slope0 * first[j] + d_value1 * second[j + 1] +
            d_slope1 * first[j + 1] + beyond};
  };
  const auto [value_row0, slope_row0] = row_integral(first_, second_);
  if (weight_ == 0.0 && d_weight_ds_ == 0.0) {  // one row: a straight edge moved, or s on a row
    out.value = value_row0;
    out.d_dx = slope_row0;
    out.d_ds = -slope_row0 * d_shift_ds_;
    return out;
  }
  const auto [value_row1, slope_row1] = row_integral(first_ + kRowSize, second_ + kRowSize);
  out.value = (1.0 - weight_) * value_row0 + weight_ * value_row1;
  out.d_dx = (1.0 - weight_) * slope_row0 + weight_ * slope_row1;
  out.d_ds = (value_row1 - value_row0) * d_weight_ds_;
  return out;
}

// V and its derivatives from H at the four corners z ± A ± B (signs + - - +).
PixelProfileValue BlurredDiskProfile::FromCorners(const Integral (&corner)[4], double a, double b) {
  const Integral &pp = corner[0], &pm = corner[1], &mp = corner[2], &mm = corner[3];
  const double per_area = 1.0 / (4.0 * a * b);
  PixelProfileValue out;
  out.value = (pp.value - pm.value - mp.value + mm.value) * per_area;
  out.d_dz = (pp.d_dx - pm.d_dx - mp.d_dx + mm.d_dx) * per_area;
  out.d_ds = (pp.d_ds - pm.d_ds - mp.d_ds + mm.d_ds) * per_area;
  // A ∂V/∂A + B ∂V/∂B: each half-width's derivative of the second difference, less 2V for
  // the 1/4AB.
  out.d_dlog_width =
      (a * (pp.d_dx - pm.d_dx + mp.d_dx - mm.d_dx) + b * (pp.d_dx + pm.d_dx - mp.d_dx - mm.d_dx)) *
          per_area -
      2.0 * out.value;
  return out;
}

#if defined(__x86_64__)
namespace {

using avx2::All;
using avx2::Gather;

// The cubic Hermite basis at four points, about the table nodes below them.
struct HermiteLanes : avx2::HermiteBasisLanes {
  __m128i node;
  __m256d d_value0, d_slope0, d_value1, d_slope1;
  __m256d beyond, half_beyond_squared;  // past kMaxZ, where G = 1
};

// One table row's H and its slope at the four points (SecondIntegralAt's row_integral).
struct RowLanes {
  __m256d value, slope;
};
MARKERBENCH_AVX2 RowLanes RowIntegralLanes(const HermiteLanes& at,
                                           const double* first,
                                           const double* second) {
  const __m256d second0 = Gather(second, at.node), first0 = Gather(first, at.node);
  const __m256d second1 = Gather(second + 1, at.node), first1 = Gather(first + 1, at.node);
  __m256d value =
      _mm256_add_pd(_mm256_mul_pd(at.value0, second0), _mm256_mul_pd(at.slope0, first0));
  value = _mm256_add_pd(value, _mm256_mul_pd(at.value1, second1));
  value = _mm256_add_pd(value, _mm256_mul_pd(at.slope1, first1));
  value = _mm256_add_pd(value, _mm256_mul_pd(at.beyond, All(first[kZSteps])));
  value = _mm256_add_pd(value, at.half_beyond_squared);
  __m256d slope =
      _mm256_add_pd(_mm256_mul_pd(at.d_value0, second0), _mm256_mul_pd(at.d_slope0, first0));
  slope = _mm256_add_pd(slope, _mm256_mul_pd(at.d_value1, second1));
  slope = _mm256_add_pd(slope, _mm256_mul_pd(at.d_slope1, first1));
  return {value, _mm256_add_pd(slope, at.beyond)};
}

}  // namespace

// SecondIntegralAt's operations on the four corners' lanes, in its order (no FMA: the target is
// AVX2 alone, so no product is fused into a sum), the tables read by gathers at nodes kept
// within the row; the lanes SecondIntegralAt returns early for are set as it sets them. The
// lanes come back out through registers: through memory, the loads of the stored vector waited
// on it, and the whole took as long as one corner at a time.
MARKERBENCH_AVX2 PixelProfileValue BlurredDiskProfile::OverPixelAvx2(double z,
                                                                     double a,
                                                                     double b) const {
  // The corners z ± A ± B as OverPixel adds them ((z + A) + B, ...), less the shift.
  const __m256d corners = _mm256_add_pd(_mm256_add_pd(All(z), _mm256_set_pd(-a, -a, a, a)),
                                        _mm256_set_pd(-b, b, -b, b));
  const __m256d x = _mm256_sub_pd(corners, All(shift_));
  const __m256d not_a_number = _mm256_cmp_pd(x, x, _CMP_UNORD_Q);
  const __m256d below = _mm256_cmp_pd(x, All(-kMaxZ), _CMP_LE_OQ);
  HermiteLanes at;
  at.beyond = _mm256_max_pd(_mm256_sub_pd(x, All(kMaxZ)), _mm256_setzero_pd());
  const __m256d xj =
      _mm256_mul_pd(_mm256_add_pd(_mm256_min_pd(All(kMaxZ), x), All(kMaxZ)), All(kPerZStep));
  const __m128i node = _mm_max_epi32(
      _mm_min_epi32(_mm256_cvttpd_epi32(xj), _mm_set1_epi32(kZSteps - 1)), _mm_setzero_si128());
  at.node = node;
  const __m256d f = _mm256_sub_pd(xj, _mm256_cvtepi32_pd(node));
  static_cast<avx2::HermiteBasisLanes&>(at) = avx2::HermiteBasis(f, kZStep);
  const __m256d f2 = _mm256_mul_pd(f, f);
  at.d_value0 = _mm256_mul_pd(
      _mm256_sub_pd(_mm256_mul_pd(All(6.0), f2), _mm256_mul_pd(All(6.0), f)), All(kPerZStep));
  at.d_value1 = _mm256_xor_pd(at.d_value0, All(-0.0));
  at.d_slope0 = _mm256_add_pd(
      _mm256_sub_pd(_mm256_mul_pd(All(3.0), f2), _mm256_mul_pd(All(4.0), f)), All(1.0));
  at.d_slope1 = _mm256_sub_pd(_mm256_mul_pd(All(3.0), f2), _mm256_mul_pd(All(2.0), f));
  at.half_beyond_squared = _mm256_mul_pd(_mm256_mul_pd(All(0.5), at.beyond), at.beyond);
  const RowLanes row0 = RowIntegralLanes(at, first_, second_);
  __m256d lanes[3];  // value, d_dx, d_ds
  if (weight_ == 0.0 && d_weight_ds_ == 0.0) {
    lanes[0] = row0.value;
    lanes[1] = row0.slope;
    lanes[2] = _mm256_mul_pd(_mm256_xor_pd(row0.slope, All(-0.0)), All(d_shift_ds_));
  } else {
    const RowLanes row1 = RowIntegralLanes(at, first_ + kRowSize, second_ + kRowSize);
    const __m256d keep = All(1.0 - weight_), take = All(weight_);
    lanes[0] = _mm256_add_pd(_mm256_mul_pd(keep, row0.value), _mm256_mul_pd(take, row1.value));
    lanes[1] = _mm256_add_pd(_mm256_mul_pd(keep, row0.slope), _mm256_mul_pd(take, row1.slope));
    lanes[2] = _mm256_mul_pd(_mm256_sub_pd(row1.value, row0.value), All(d_weight_ds_));
  }
  // Below the table zero, then at a NaN point NaN; each lane out of its register.
  double returned[3][4];
  for (int i = 0; i < 3; ++i) {
    const __m256d v =
        _mm256_blendv_pd(_mm256_andnot_pd(below, lanes[i]), All(kNotANumber), not_a_number);
    const __m128d low = _mm256_castpd256_pd128(v), high = _mm256_extractf128_pd(v, 1);
    returned[i][0] = _mm_cvtsd_f64(low);
    returned[i][1] = _mm_cvtsd_f64(_mm_unpackhi_pd(low, low));
    returned[i][2] = _mm_cvtsd_f64(high);
    returned[i][3] = _mm_cvtsd_f64(_mm_unpackhi_pd(high, high));
  }
  Integral corner[4];
  for (int k = 0; k < 4; ++k) corner[k] = {returned[0][k], returned[1][k], returned[2][k]};
  return FromCorners(corner, a, b);
}
#else
PixelProfileValue BlurredDiskProfile::OverPixelAvx2(double z, double a, double b) const {
  return OverPixel(z, a, b, Corners::kOneByOne);
}
#endif

PixelProfileValue BlurredDiskProfile::OverPixel(double z, double a, double b) const {
  return OverPixel(z, a, b, kCpuHasAvx2 ? Corners::kAvx2 : Corners::kOneByOne);
}

PixelProfileValue BlurredDiskProfile::OverPixel(double z,
                                                double a,
                                                double b,
                                                Corners corners) const {
  a = std::max(a, 1e-3);
  b = std::max(b, 1e-3);
  if (corners == Corners::kAvx2 && kCpuHasAvx2) return OverPixelAvx2(z, a, b);
  // The four corners of the second difference: z ± A ± B, signs + - - +.
  const Integral corner[4] = {SecondIntegralAt(z + a + b),
                              SecondIntegralAt(z + a - b),
                              SecondIntegralAt(z - a + b),
                              SecondIntegralAt(z - a - b)};
  return FromCorners(corner, a, b);
}

}  // namespace markerbench
