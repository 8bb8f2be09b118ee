// 95 % confidence intervals for the figures a sweep cell reports from its sample of frames:
// rates (Wilson score interval) and medians (the distribution-free order-statistic interval).
#pragma once

#include <cmath>
#include <vector>

namespace markerbench {

struct Interval {
  double lo = NAN;
  double hi = NAN;
};

inline constexpr double kConfidence = 0.95;

// Wilson score interval for a rate of `successes` in `n` trials (Wilson 1927): unlike the
// normal interval it stays inside [0, 1] and keeps its coverage near 0 % and 100 %. NaN when
// n is 0.
Interval WilsonInterval(int successes, int n, double confidence = kConfidence);
// The same for a rate p observed with an effective sample size n: for clustered samples
// (a video's frames, which are lost in runs), the number of clusters, which is conservative.
Interval WilsonIntervalOfRate(double p, double n, double confidence = kConfidence);

// Interval for the median of the distribution `values` (NaN values dropped) come from: the
// order statistics x_(j) and x_(n+1-j), with j the largest rank such that
// P(B <= j-1) <= (1 - confidence)/2 for B ~ Binomial(n, 1/2). Its coverage is at least
// `confidence` for any continuous distribution, and it needs neither resampling (a bootstrap
// would add Monte Carlo noise and cost) nor a model. NaN when n is too small for any
// interval to reach the confidence (n < 6 at 95 %).
Interval MedianInterval(std::vector<double> values, double confidence = kConfidence);

}  // namespace markerbench
