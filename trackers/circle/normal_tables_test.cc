// The tabulated normal functions against their closed forms, inside and beyond the tables.
#include "trackers/circle/normal_tables.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "trackers/circle/blurred_design.h"

namespace markerbench {
namespace {

TEST(NormalTailTable, MatchesTheNormalTail) {
  for (double z = -12.0; z <= 30.0; z += 0.0371) {
    SCOPED_TRACE("z " + std::to_string(z));
    const double tail = 0.5 * std::erfc(z / std::sqrt(2.0));
    const double mills = NormalDensity(z) / tail;
    const NormalTailTable::Values values = kNormalTailTable.At(z);
    EXPECT_NEAR(values.minus_log_tail, -std::log(tail), 1e-6 * std::max(1.0, -std::log(tail)));
    EXPECT_NEAR(values.mills, mills, 1e-6 * std::max(1.0, mills));
    EXPECT_NEAR(values.mills_excess, mills - z, 1e-6);
  }
}

TEST(NormalCdfTable, MatchesTheNormalCdfAndDensity) {
  for (double z = -12.0; z <= 12.0; z += 0.00371) {
    SCOPED_TRACE("z " + std::to_string(z));
    const NormalCdfTable::Values values = kNormalCdfTable.At(z);
    EXPECT_NEAR(values.cdf, NormalCdf(z), 2e-10);
    EXPECT_NEAR(values.density, NormalDensity(z), 2e-10);
  }
  EXPECT_EQ(kNormalCdfTable.At(-NormalCdfTable::kEnd).cdf, 0.0);
  EXPECT_EQ(kNormalCdfTable.At(NormalCdfTable::kEnd).cdf, 1.0);
  EXPECT_EQ(kNormalCdfTable.At(std::nan("")).density, 0.0);
}

#if defined(__x86_64__)
// At's and Cdf's four lanes of z, through AVX2 vectors.
struct FourValues {
  double cdf[4], density[4], cdf_alone[4];
};
MARKERBENCH_AVX2 FourValues InLanes(const double (&z)[4]) {
  const __m256d lanes = _mm256_loadu_pd(z);
  const NormalCdfTable::Lanes at = kNormalCdfTable.AtLanes(lanes);
  FourValues out;
  _mm256_storeu_pd(out.cdf, at.cdf);
  _mm256_storeu_pd(out.density, at.density);
  _mm256_storeu_pd(out.cdf_alone, kNormalCdfTable.CdfLanes(lanes));
  return out;
}

// Four z in the lanes of a vector give At's and Cdf's bits one by one: inside the table, on its
// nodes and ends, beyond both, and at NaN and infinite z.
TEST(NormalCdfTable, LanesGiveTheBitsOfOneByOne) {
  if (!kCpuHasAvx2) GTEST_SKIP() << "no AVX2 on this CPU";
  const double end = NormalCdfTable::kEnd;
  std::vector<double> points = {-HUGE_VAL,
                                -1e300,
                                -end - 1e-9,
                                -end,
                                -end + 1e-12,
                                end - 1e-12,
                                end,
                                end + 1e-9,
                                1e300,
                                HUGE_VAL,
                                std::nan("")};
  for (double z = -10.0; z <= 10.0; z += 0.00371) points.push_back(z);
  for (int node = 0; node < NormalCdfTable::kNodes; ++node) {
    points.push_back(-end + static_cast<double>(node) / NormalCdfTable::kPerUnit);
  }
  while (points.size() % 4 != 0) points.push_back(0.0);
  for (size_t i = 0; i < points.size(); i += 4) {
    const double z[4] = {points[i], points[i + 1], points[i + 2], points[i + 3]};
    const FourValues lanes = InLanes(z);
    for (int k = 0; k < 4; ++k) {
      const NormalCdfTable::Values one = kNormalCdfTable.At(z[k]);
      const double cdf_alone = kNormalCdfTable.Cdf(z[k]);
      ASSERT_EQ(std::memcmp(&one.cdf, &lanes.cdf[k], sizeof(double)), 0) << "z " << z[k];
      ASSERT_EQ(std::memcmp(&one.density, &lanes.density[k], sizeof(double)), 0) << "z " << z[k];
      ASSERT_EQ(std::memcmp(&cdf_alone, &lanes.cdf_alone[k], sizeof(double)), 0) << "z " << z[k];
    }
  }
}
#endif

}  // namespace
}  // namespace markerbench
