#include "trackers/circle/normal_tables.h"

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

NormalCdfTable::NormalCdfTable() {
  for (int i = 0; i < kNodes; ++i) {
    const double z = -kEnd + static_cast<double>(i) / kPerUnit;
    cdf_[i] = NormalCdf(z);
    density_[i] = NormalDensity(z);
    density_slope_[i] = -z * density_[i];
  }
}

const NormalCdfTable kNormalCdfTable;

#if defined(__x86_64__)
namespace {

using avx2::All;
using avx2::Gather;

// HermiteWeights at four z within the table, and which of them lie beyond its ends (a NaN
// below it, as At's tests take it); their nodes are kept within the table for the gathers.
struct HermiteLanes : avx2::HermiteBasisLanes {
  __m128i node;
  __m256d below, above;

  MARKERBENCH_AVX2 HermiteLanes(__m256d z, double end, int per_unit, int nodes) {
    below = _mm256_cmp_pd(z, All(-end), _CMP_NGT_UQ);  // !(z > -end)
    above = _mm256_cmp_pd(z, All(end), _CMP_NLT_UQ);   // !(z < end)
    const __m256d x = _mm256_mul_pd(_mm256_add_pd(z, All(end)), All(per_unit));
    node = _mm_max_epi32(_mm_min_epi32(_mm256_cvttpd_epi32(x), _mm_set1_epi32(nodes - 2)),
                         _mm_setzero_si128());
    static_cast<avx2::HermiteBasisLanes&>(*this) =
        avx2::HermiteBasis(_mm256_sub_pd(x, _mm256_cvtepi32_pd(node)), 1.0 / per_unit);
  }

  // HermiteWeights::Of, its values at the node and the next already gathered.
  MARKERBENCH_AVX2 __m256d Of(__m256d values0,
                              __m256d slopes0,
                              __m256d values1,
                              __m256d slopes1) const {
    __m256d of = _mm256_add_pd(_mm256_mul_pd(value0, values0), _mm256_mul_pd(slope0, slopes0));
    of = _mm256_add_pd(of, _mm256_mul_pd(value1, values1));
    return _mm256_add_pd(of, _mm256_mul_pd(slope1, slopes1));
  }
};

}  // namespace

NormalCdfTable::Lanes NormalCdfTable::AtLanes(__m256d z) const {
  const HermiteLanes at(z, kEnd, kPerUnit, kNodes);
  const __m128i next = _mm_add_epi32(at.node, _mm_set1_epi32(1));
  const __m256d density0 = Gather(density_.data(), at.node);
  const __m256d density1 = Gather(density_.data(), next);
  const __m256d cdf =
      at.Of(Gather(cdf_.data(), at.node), density0, Gather(cdf_.data(), next), density1);
  const __m256d density = at.Of(density0,
                                Gather(density_slope_.data(), at.node),
                                density1,
                                Gather(density_slope_.data(), next));
  // Below the table 0 and 0, above it 1 and 0.
  return {_mm256_andnot_pd(at.below, _mm256_blendv_pd(cdf, All(1.0), at.above)),
          _mm256_andnot_pd(_mm256_or_pd(at.below, at.above), density)};
}

__m256d NormalCdfTable::CdfLanes(__m256d z) const {
  const HermiteLanes at(z, kEnd, kPerUnit, kNodes);
  const __m128i next = _mm_add_epi32(at.node, _mm_set1_epi32(1));
  const __m256d cdf = at.Of(Gather(cdf_.data(), at.node),
                            Gather(density_.data(), at.node),
                            Gather(cdf_.data(), next),
                            Gather(density_.data(), next));
  return _mm256_andnot_pd(at.below, _mm256_blendv_pd(cdf, All(1.0), at.above));
}
#endif

}  // namespace markerbench
