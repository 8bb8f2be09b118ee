#include "trackers/circle/normal_tables.h"

#include "trackers/circle/blurred_design.h"

namespace markerbench {

NormalTailTable::NormalTailTable() {
  for (int i = 0; i < kNodes; ++i) {
    const double z = -kEnd + static_cast<double>(i) / kPerUnit;
    const double tail = 0.5 * std::erfc(z / std::sqrt(2.0));
    const double mills = NormalDensity(z) / tail;
    rows_[i] = {-std::log(tail), mills, mills * (mills - z)};
  }
}

const NormalTailTable kNormalTailTable;

NormalCdfTable::NormalCdfTable() {
  for (int i = 0; i < kNodes; ++i) {
    const double z = -kEnd + static_cast<double>(i) / kPerUnit;
    const double density = NormalDensity(z);
    rows_[i] = {NormalCdf(z), density, -z * density, 0.0};
  }
}

const NormalCdfTable kNormalCdfTable;

#if defined(__x86_64__)
namespace {

using avx2::All;

// HermiteWeights at four z within the table, and which of them lie beyond its ends (a NaN
// below it, as At's tests take it); their nodes are kept within the table for the reads.
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

  // HermiteWeights::Of, its values at the node and the next already read.
  MARKERBENCH_AVX2 __m256d Of(__m256d values0,
                              __m256d slopes0,
                              __m256d values1,
                              __m256d slopes1) const {
    __m256d of = _mm256_add_pd(_mm256_mul_pd(value0, values0), _mm256_mul_pd(slope0, slopes0));
    of = _mm256_add_pd(of, _mm256_mul_pd(value1, values1));
    return _mm256_add_pd(of, _mm256_mul_pd(slope1, slopes1));
  }
};

// The rows of the four lanes' nodes (4 doubles each) as columns: Φ, φ and φ' of the lanes.
struct TableColumns {
  __m256d cdf, density, density_slope;
};
MARKERBENCH_AVX2 TableColumns
ColumnsOf(const std::array<std::array<double, 4>, NormalCdfTable::kNodes>& rows, __m128i node) {
  const __m256d a = _mm256_load_pd(rows[_mm_extract_epi32(node, 0)].data());
  const __m256d b = _mm256_load_pd(rows[_mm_extract_epi32(node, 1)].data());
  const __m256d c = _mm256_load_pd(rows[_mm_extract_epi32(node, 2)].data());
  const __m256d d = _mm256_load_pd(rows[_mm_extract_epi32(node, 3)].data());
  const __m256d ab_low = _mm256_unpacklo_pd(a, b), ab_high = _mm256_unpackhi_pd(a, b);
  const __m256d cd_low = _mm256_unpacklo_pd(c, d), cd_high = _mm256_unpackhi_pd(c, d);
  return {_mm256_permute2f128_pd(ab_low, cd_low, 0x20),
          _mm256_permute2f128_pd(ab_high, cd_high, 0x20),
          _mm256_permute2f128_pd(ab_low, cd_low, 0x31)};
}

}  // namespace

NormalCdfTable::Lanes NormalCdfTable::AtLanes(__m256d z) const {
  const HermiteLanes at(z, kEnd, kPerUnit, kNodes);
  const TableColumns here = ColumnsOf(rows_, at.node);
  const TableColumns next = ColumnsOf(rows_, _mm_add_epi32(at.node, _mm_set1_epi32(1)));
  const __m256d cdf = at.Of(here.cdf, here.density, next.cdf, next.density);
  const __m256d density = at.Of(here.density, here.density_slope, next.density, next.density_slope);
  // Below the table 0 and 0, above it 1 and 0.
  return {_mm256_andnot_pd(at.below, _mm256_blendv_pd(cdf, All(1.0), at.above)),
          _mm256_andnot_pd(_mm256_or_pd(at.below, at.above), density)};
}

__m256d NormalCdfTable::CdfLanes(__m256d z) const {
  const HermiteLanes at(z, kEnd, kPerUnit, kNodes);
  const TableColumns here = ColumnsOf(rows_, at.node);
  const TableColumns next = ColumnsOf(rows_, _mm_add_epi32(at.node, _mm_set1_epi32(1)));
  const __m256d cdf = at.Of(here.cdf, here.density, next.cdf, next.density);
  return _mm256_andnot_pd(at.below, _mm256_blendv_pd(cdf, All(1.0), at.above));
}
#endif

}  // namespace markerbench
