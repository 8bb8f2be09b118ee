// The intervals against published values and against their promised coverage, by simulation.
#include "bench/metrics/intervals.h"

#include <gtest/gtest.h>

#include <random>

namespace markerbench {
namespace {

// Newcombe (1998), Table I, method 3 (Wilson score without continuity correction).
TEST(IntervalsTest, WilsonMatchesNewcombesTable) {
  const Interval a = WilsonInterval(81, 263);
  EXPECT_NEAR(a.lo, 0.2553, 5e-5);
  EXPECT_NEAR(a.hi, 0.3662, 5e-5);
  const Interval b = WilsonInterval(15, 148);
  EXPECT_NEAR(b.lo, 0.0624, 5e-5);
  EXPECT_NEAR(b.hi, 0.1605, 5e-5);
  const Interval none = WilsonInterval(0, 20);
  EXPECT_EQ(none.lo, 0.0);
  EXPECT_NEAR(none.hi, 0.1611, 5e-5);
  const Interval all = WilsonInterval(29, 29);
  EXPECT_NEAR(all.lo, 0.8830, 5e-5);
  EXPECT_EQ(all.hi, 1.0);
  EXPECT_TRUE(std::isnan(WilsonInterval(0, 0).lo));
  for (const int n : {7, 1650, 2400}) {
    EXPECT_EQ(WilsonInterval(0, n).lo, 0.0) << n;
    EXPECT_EQ(WilsonInterval(n, n).hi, 1.0) << n;
  }
}

// A rate with an effective sample size (a video's frames counted as one sample per video):
// the integer form's interval at the same rate and size, wider than the frames' own.
TEST(IntervalsTest, WilsonOfARateWithAnEffectiveSize) {
  const Interval as_count = WilsonInterval(3, 10);
  const Interval as_rate = WilsonIntervalOfRate(0.3, 10);
  EXPECT_DOUBLE_EQ(as_rate.lo, as_count.lo);
  EXPECT_DOUBLE_EQ(as_rate.hi, as_count.hi);
  const Interval frames = WilsonInterval(495, 1650);
  EXPECT_LT(as_rate.lo, frames.lo);
  EXPECT_GT(as_rate.hi, frames.hi);
  EXPECT_TRUE(std::isnan(WilsonIntervalOfRate(0.5, 0.0).lo));
}

// For n = 100 the ranks are 40 and 61 (the textbook values: P(B <= 39) = 0.0176 and
// P(B <= 40) = 0.0284 for B ~ Binomial(100, 1/2)).
TEST(IntervalsTest, MedianIntervalUsesTheBinomialRanks) {
  std::vector<double> values;
  for (int i = 100; i >= 1; --i) values.push_back(i);  // any order
  values.push_back(NAN);                               // dropped
  const Interval m = MedianInterval(values);
  EXPECT_EQ(m.lo, 40.0);
  EXPECT_EQ(m.hi, 61.0);
  EXPECT_TRUE(std::isnan(MedianInterval({1, 2, 3, 4, 5}).lo));  // 5 samples cannot reach 95 %
  const Interval six = MedianInterval({6, 1, 5, 2, 4, 3});      // P(B <= 0) = 1/64
  EXPECT_EQ(six.lo, 1.0);
  EXPECT_EQ(six.hi, 6.0);
}

// Simulated coverage of the true median (lognormal, median 1) and of the true rate: at least
// 95 % within the simulation's error (2000 samples: ±1 %), for small and large n.
TEST(IntervalsTest, CoverageIsAtLeastTheConfidence) {
  std::mt19937_64 random(5);
  std::lognormal_distribution<double> errors(0.0, 1.0);
  for (const int n : {10, 25, 100}) {
    int median_hits = 0, rate_hits = 0;
    const int samples = 2000;
    for (int s = 0; s < samples; ++s) {
      std::vector<double> values(static_cast<size_t>(n));
      int successes = 0;
      for (double& v : values) {
        v = errors(random);
        successes += v < 1.5;  // true rate: P(lognormal < 1.5) = Phi(ln 1.5) = 0.6577
      }
      const Interval m = MedianInterval(values);
      median_hits += m.lo <= 1.0 && 1.0 <= m.hi;
      const Interval r = WilsonInterval(successes, n);
      rate_hits += r.lo <= 0.6577 && 0.6577 <= r.hi;
    }
    EXPECT_GE(median_hits, 0.94 * samples) << n;
    EXPECT_GE(rate_hits, 0.93 * samples) << n;  // Wilson's coverage oscillates around 95 %
  }
}

}  // namespace
}  // namespace markerbench
