// Gauss-Legendre quadrature: the three-point rule's closed form; exact for polynomials of
// degree below 2N; nodes in (0, 1), increasing and symmetric about 1/2; positive weights
// summing to 1.
#include "core/gauss_legendre.h"

#include <gtest/gtest.h>

#include <cmath>

namespace markerbench {
namespace {

template <int N>
void ExpectGaussLegendre() {
  const GaussLegendre<N> rule;
  double sum = 0.0;
  for (int i = 0; i < N; ++i) {
    EXPECT_GT(rule.x[i], 0.0);
    EXPECT_LT(rule.x[i], 1.0);
    if (i > 0) {
      EXPECT_GT(rule.x[i], rule.x[i - 1]);
    }
    EXPECT_NEAR(rule.x[i] + rule.x[N - 1 - i], 1.0, 1e-14);
    EXPECT_GT(rule.w[i], 0.0);
    EXPECT_NEAR(rule.w[i], rule.w[N - 1 - i], 1e-14);
    sum += rule.w[i];
  }
  EXPECT_NEAR(sum, 1.0, 1e-14);
  // ∫₀¹ (2x - 1)^d dx = 1/(d + 1) for even d, 0 for odd.
  const auto integral = [&](int degree) {
    double total = 0.0;
    for (int i = 0; i < N; ++i) total += rule.w[i] * std::pow(2.0 * rule.x[i] - 1.0, degree);
    return total;
  };
  for (int degree = 0; degree < 2 * N; ++degree) {
    EXPECT_NEAR(integral(degree), degree % 2 ? 0.0 : 1.0 / (degree + 1), 1e-13)
        << "N " << N << " degree " << degree;
  }
}

// The three-point rule in closed form: nodes (1 - sqrt(3/5))/2, 1/2 and (1 + sqrt(3/5))/2,
// weights 5/18, 4/9 and 5/18; wrong for (2x - 1)^6 (3/25 against 1/7).
TEST(GaussLegendre, IsTheThreePointRule) {
  const GaussLegendre<3> rule;
  EXPECT_NEAR(rule.x[0], 0.5 * (1.0 - std::sqrt(0.6)), 1e-14);
  EXPECT_NEAR(rule.x[1], 0.5, 1e-14);
  EXPECT_NEAR(rule.x[2], 0.5 * (1.0 + std::sqrt(0.6)), 1e-14);
  EXPECT_NEAR(rule.w[0], 5.0 / 18.0, 1e-14);
  EXPECT_NEAR(rule.w[1], 4.0 / 9.0, 1e-14);
  double sixth = 0.0;
  for (int i = 0; i < 3; ++i) sixth += rule.w[i] * std::pow(2.0 * rule.x[i] - 1.0, 6);
  EXPECT_NEAR(sixth, 3.0 / 25.0, 1e-14);
}

TEST(GaussLegendre, IntegratesPolynomialsBelowTwiceItsNodesExactly) {
  ExpectGaussLegendre<3>();
  ExpectGaussLegendre<16>();
  ExpectGaussLegendre<32>();
  ExpectGaussLegendre<48>();
}

}  // namespace
}  // namespace markerbench
