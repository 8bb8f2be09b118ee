#include "bench/metrics/intervals.h"

#include <algorithm>

namespace markerbench {
namespace {

// The standard normal quantile of `p` in (0.5, 1), by bisection on erfc (to 1e-12).
double NormalQuantile(double p) {
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (1.0 - 0.5 * std::erfc(mid / std::sqrt(2.0)) < p) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace

Interval WilsonInterval(int successes, int n, double confidence) {
  if (n <= 0) return {};
  return WilsonIntervalOfRate(static_cast<double>(successes) / n, n, confidence);
}

Interval WilsonIntervalOfRate(double p, double n, double confidence) {
  if (!(n > 0.0)) return {};
  const double z = NormalQuantile(0.5 + 0.5 * confidence);
  const double z2n = z * z / n;
  const double centre = (p + 0.5 * z2n) / (1.0 + z2n);
  const double half = z * std::sqrt(p * (1.0 - p) / n + 0.25 * z2n / n) / (1.0 + z2n);
  // At p = 0 or 1 the bound is the end itself (the two terms cancel but for rounding).
  return {p <= 0.0 ? 0.0 : std::max(0.0, centre - half),
          p >= 1.0 ? 1.0 : std::min(1.0, centre + half)};
}

Interval MedianInterval(std::vector<double> values, double confidence) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return std::isnan(v); }),
               values.end());
  const int n = static_cast<int>(values.size());
  const double tail = 0.5 * (1.0 - confidence);
  // The largest j with P(B <= j-1) <= tail, from the binomial pmf in logs (n may be large).
  const double log_half_n = n * std::log(0.5);
  double cdf = 0.0;
  int j = 0;
  for (int k = 0; k < n; ++k) {
    cdf += std::exp(std::lgamma(n + 1.0) - std::lgamma(k + 1.0) - std::lgamma(n - k + 1.0) +
                    log_half_n);
    if (cdf > tail) break;
    j = k + 1;
  }
  if (j == 0) return {};
  std::sort(values.begin(), values.end());
  return {values[static_cast<size_t>(j - 1)], values[static_cast<size_t>(n - j)]};
}

}  // namespace markerbench
