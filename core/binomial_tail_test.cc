#include "core/binomial_tail.h"

#include <gtest/gtest.h>

#include <cmath>

namespace markerbench {
namespace {

TEST(FairBinomialUpperTail, MatchesClosedForms) {
  EXPECT_DOUBLE_EQ(FairBinomialUpperTail(12, 12), std::pow(0.5, 12));
  EXPECT_NEAR(FairBinomialUpperTail(8, 5), 93.0 / 256.0, 1e-12);  // (56 + 28 + 8 + 1) / 256
  EXPECT_NEAR(FairBinomialUpperTail(5, 1), 31.0 / 32.0, 1e-12);
  EXPECT_DOUBLE_EQ(FairBinomialUpperTail(5, 0), 1.0);
  EXPECT_DOUBLE_EQ(FairBinomialUpperTail(5, 6), 0.0);
  // Symmetry: P(X >= k) + P(X >= n - k + 1) = 1; for odd n, P(X >= (n + 1)/2) = 1/2, also
  // where C(n, k) and 2^n overflow a double.
  EXPECT_NEAR(FairBinomialUpperTail(15, 4) + FairBinomialUpperTail(15, 12), 1.0, 1e-12);
  EXPECT_NEAR(FairBinomialUpperTail(2001, 1001), 0.5, 1e-9);
}

}  // namespace
}  // namespace markerbench
