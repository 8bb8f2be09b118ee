// The tabulated normal functions against their closed forms, inside and beyond the tables.
#include "trackers/circle/normal_tables.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

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

}  // namespace
}  // namespace markerbench
