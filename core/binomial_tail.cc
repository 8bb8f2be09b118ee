#include "core/binomial_tail.h"

#include <algorithm>
#include <cmath>

namespace markerbench {

double FairBinomialUpperTail(int n, int k) {
  if (k <= 0) return 1.0;
  // Σ_{j >= k} C(n, j) / 2^n.
  double tail = 0.0;
  for (int j = k; j <= n; ++j) {
    tail += std::exp(std::lgamma(n + 1.0) - std::lgamma(j + 1.0) - std::lgamma(n - j + 1.0) -
                     n * std::log(2.0));
  }
  return std::min(1.0, tail);
}

}  // namespace markerbench
