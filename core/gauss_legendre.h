// Gauss-Legendre quadrature on [0, 1]: ∫₀¹ f ≈ Σ w_i f(x_i), exact for polynomials of degree
// below 2N. The nodes are the roots of the Legendre polynomial P_N, found by Newton's method
// from Chebyshev guesses, in increasing order.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace markerbench {

template <int N>
struct GaussLegendre {
  std::array<double, N> x{}, w{};
  GaussLegendre() {
    constexpr double kPi = 3.14159265358979323846;
    for (int i = 0; i < N; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (N + 0.5)), dp = 1.0;
      for (int iteration = 0; iteration < 100; ++iteration) {
        double p0 = 1.0, p1 = z;  // P_0, P_1, then up to P_N by the three-term recurrence
        for (int j = 2; j <= N; ++j) {
          const double p2 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p0) / j;
          p0 = p1;
          p1 = p2;
        }
        dp = N * (z * p1 - p0) / (z * z - 1.0);
        const double step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-15) break;
      }
      x[static_cast<size_t>(i)] = 0.5 * (1.0 - z);
      w[static_cast<size_t>(i)] = 1.0 / ((1.0 - z * z) * dp * dp);
    }
  }
};

}  // namespace markerbench
