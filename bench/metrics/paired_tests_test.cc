#include "bench/metrics/paired_tests.h"

#include <gtest/gtest.h>

#include <cmath>

namespace markerbench {
namespace {

TEST(PairedTests, McNemarIsTheBinomialTailOfTheDiscordantPairs) {
  EXPECT_DOUBLE_EQ(McNemarPValue(10, 0), std::pow(0.5, 10));
  EXPECT_NEAR(McNemarPValue(3, 3), 42.0 / 64.0, 1e-12);  // P(X >= 3), X ~ B(6, 1/2)
  EXPECT_DOUBLE_EQ(McNemarPValue(0, 5), 1.0);
  EXPECT_NEAR(McNemarPValue(600, 400), 1.3642e-10, 0.0001e-10);  // large n stays finite
}

TEST(PairedTests, SignedRankExactTailCountsSignAssignments) {
  EXPECT_NEAR(WilcoxonSignedRankPValue({1, 2, 3, 4, 5}), 1.0 / 32.0, 1e-12);
  // W+ = 12 of 15: the subsets of {1..5} with sum >= 12 are the complements of those with
  // sum <= 3: {}, {1}, {2}, {3}, {1,2}.
  EXPECT_NEAR(WilcoxonSignedRankPValue({1, 2, -3, 4, 5}), 5.0 / 32.0, 1e-12);
  EXPECT_DOUBLE_EQ(WilcoxonSignedRankPValue({-1, -2, -3}), 1.0);  // every sum is >= 0
  EXPECT_DOUBLE_EQ(WilcoxonSignedRankPValue({0, 0, 0}), 1.0);     // zeros are dropped
  // Ties get mid-ranks: |d| = 1, 1, 2 -> ranks 1.5, 1.5, 3; W+ = 4.5 with the 3 and one 1.5.
  // Sums of 8 sign patterns: 0, 1.5, 1.5, 3, 3, 4.5, 4.5, 6 -> P(W+ >= 4.5) = 3/8.
  EXPECT_NEAR(WilcoxonSignedRankPValue({1, -1, 2}), 3.0 / 8.0, 1e-12);
}

TEST(PairedTests, SignedRankNormalApproximationBeyondTheExactRange) {
  // d_i = (-1)^i i for i = 1..200: W+ = 2 + 4 + ... + 200 = 10100.
  std::vector<double> d;
  for (int i = 1; i <= 200; ++i) d.push_back(i % 2 == 0 ? i : -i);
  const double mean = 200.0 * 201.0 / 4.0;
  const double sd = std::sqrt(200.0 * 201.0 * 401.0 / 24.0);
  const double z = (10100.0 - mean - 0.5) / sd;
  EXPECT_NEAR(WilcoxonSignedRankPValue(d), 0.5 * std::erfc(z / std::sqrt(2.0)), 1e-12);
  // At the switch both agree closely: 100 and 101 alternating differences.
  std::vector<double> exact, normal;
  for (int i = 1; i <= kExactSignedRankMax; ++i) exact.push_back(i % 3 == 0 ? -i : i);
  normal = exact;
  normal.push_back(1e9);  // one more, largest and positive
  const double p_exact = WilcoxonSignedRankPValue(exact);
  EXPECT_LT(p_exact, 0.01);
  EXPECT_LT(WilcoxonSignedRankPValue(normal), p_exact);
  EXPECT_GT(WilcoxonSignedRankPValue(normal), 0.2 * p_exact);
}

TEST(PairedTests, MannWhitneyNormalApproximation) {
  // U = 9 of 9, mean 4.5, variance 3·3·7/12 = 5.25, continuity-corrected z = 4 / sqrt(5.25).
  const double z = 4.0 / std::sqrt(5.25);
  EXPECT_NEAR(MannWhitneyPValue({4, 5, 6}, {1, 2, 3}), 0.5 * std::erfc(z / std::sqrt(2.0)), 1e-12);
  EXPECT_GT(MannWhitneyPValue({1, 2, 3}, {4, 5, 6}), 0.9);
  EXPECT_DOUBLE_EQ(MannWhitneyPValue({}, {1.0}), 1.0);
  EXPECT_DOUBLE_EQ(MannWhitneyPValue({2, 2}, {2, 2}), 1.0);  // all tied: no evidence
}

TEST(PairedTests, HolmStepDown) {
  const std::vector<double> adjusted = HolmAdjusted({0.01, 0.04, 0.03, 0.005});
  // Sorted: 0.005·4 = 0.02, 0.01·3 = 0.03, 0.03·2 = 0.06, 0.04·1 -> kept monotone at 0.06.
  const std::vector<double> expected = {0.03, 0.06, 0.06, 0.02};
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(adjusted[i], expected[i], 1e-12);
  EXPECT_DOUBLE_EQ(HolmAdjusted({0.9, 0.8})[0], 1.0);  // capped at 1
}

}  // namespace
}  // namespace markerbench
