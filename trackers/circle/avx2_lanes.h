// What the circle tracker's AVX2 inner loops share (blurred_disk_profile.cc, normal_tables.cc,
// blurred_ellipse.cc): whether the CPU has AVX2, read once at load, and the helpers of their
// lanes. Their code is compiled for AVX2 alone, not FMA, so no product is fused into a sum and
// each lane rounds as the scalar code it mirrors does: the same bits (tested beside each).
#pragma once

#if defined(__x86_64__)
#include <immintrin.h>

#define MARKERBENCH_AVX2 __attribute__((target("avx2")))
#endif

namespace markerbench {

// Whether the CPU runs AVX2: a plain bool read at load (a function's static would test its
// guard at every call, per pixel and edge).
#if defined(__x86_64__)
extern const bool kCpuHasAvx2;
#else
constexpr bool kCpuHasAvx2 = false;
#endif

#if defined(__x86_64__)
namespace avx2 {

MARKERBENCH_AVX2 inline __m256d All(double value) { return _mm256_set1_pd(value); }

// row[node] in each lane.
MARKERBENCH_AVX2 inline __m256d Gather(const double* row, __m128i node) {
  const __m256d every_lane = _mm256_castsi256_pd(_mm256_set1_epi64x(-1));
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), row, node, every_lane, 8);
}

// The cubic Hermite basis at t in [0, 1] between table nodes `step` apart: the weights of the
// values and the slopes at the node below and at the next, in HermiteWeights' order of
// operations (normal_tables.h).
struct HermiteBasisLanes {
  __m256d value0, slope0, value1, slope1;
};
MARKERBENCH_AVX2 inline HermiteBasisLanes HermiteBasis(__m256d t, double step) {
  const __m256d t2 = _mm256_mul_pd(t, t), t3 = _mm256_mul_pd(t2, t);
  HermiteBasisLanes basis;
  basis.value0 = _mm256_add_pd(
      _mm256_sub_pd(_mm256_mul_pd(All(2.0), t3), _mm256_mul_pd(All(3.0), t2)), All(1.0));
  basis.slope0 =
      _mm256_mul_pd(_mm256_add_pd(_mm256_sub_pd(t3, _mm256_mul_pd(All(2.0), t2)), t), All(step));
  basis.value1 = _mm256_sub_pd(All(1.0), basis.value0);
  basis.slope1 = _mm256_mul_pd(_mm256_sub_pd(t3, t2), All(step));
  return basis;
}

}  // namespace avx2
#endif

}  // namespace markerbench
