#include "bench/metrics/paired_tests.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/binomial_tail.h"

namespace markerbench {
namespace {

// P(Z >= z) for a standard normal Z.
double UpperNormalTail(double z) { return 0.5 * std::erfc(z / std::sqrt(2.0)); }

// Mid-ranks (1-based) of `values`, and the tie correction Σ (t³ - t) over groups of ties.
std::vector<double> MidRanks(const std::vector<double>& values, double* tie_term) {
  std::vector<size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return values[a] < values[b]; });
  std::vector<double> ranks(values.size());
  *tie_term = 0.0;
  for (size_t i = 0; i < order.size();) {
    size_t j = i;
    while (j + 1 < order.size() && values[order[j + 1]] == values[order[i]]) ++j;
    const double t = static_cast<double>(j - i + 1);
    for (size_t k = i; k <= j; ++k) ranks[order[k]] = 0.5 * static_cast<double>(i + j) + 1.0;
    *tie_term += t * t * t - t;
    i = j + 1;
  }
  return ranks;
}

// P(W+ >= observed) under random signs, for ranks that are multiples of 1/2: the
// distribution of the sum of doubled ranks by dynamic programming.
double ExactSignedRankTail(const std::vector<double>& ranks, double w_plus) {
  std::vector<int> doubled;
  int total = 0;
  for (const double r : ranks) {
    doubled.push_back(static_cast<int>(std::lround(2.0 * r)));
    total += doubled.back();
  }
  std::vector<double> probability(static_cast<size_t>(total) + 1, 0.0);
  probability[0] = 1.0;
  int reach = 0;
  for (const int d : doubled) {
    reach += d;
    for (int s = reach; s >= d; --s) {
      probability[s] = 0.5 * (probability[s] + probability[s - d]);
    }
    for (int s = d - 1; s >= 0; --s) probability[s] *= 0.5;
  }
  const int observed = static_cast<int>(std::lround(2.0 * w_plus));
  double tail = 0.0;
  for (int s = observed; s <= total; ++s) tail += probability[s];
  return std::min(1.0, tail);
}

}  // namespace

double McNemarPValue(int lost, int gained) { return FairBinomialUpperTail(lost + gained, lost); }

double WilcoxonSignedRankPValue(const std::vector<double>& differences) {
  std::vector<double> magnitudes;
  std::vector<bool> positive;
  for (const double d : differences) {
    if (d == 0.0 || std::isnan(d)) continue;
    magnitudes.push_back(std::abs(d));
    positive.push_back(d > 0.0);
  }
  const size_t n = magnitudes.size();
  if (n == 0) return 1.0;
  double tie_term = 0.0;
  const std::vector<double> ranks = MidRanks(magnitudes, &tie_term);
  double w_plus = 0.0;
  for (size_t i = 0; i < n; ++i) {
    if (positive[i]) w_plus += ranks[i];
  }
  if (n <= static_cast<size_t>(kExactSignedRankMax)) return ExactSignedRankTail(ranks, w_plus);
  const double nd = static_cast<double>(n);
  const double mean = nd * (nd + 1.0) / 4.0;
  const double variance = nd * (nd + 1.0) * (2.0 * nd + 1.0) / 24.0 - tie_term / 48.0;
  if (variance <= 0.0) return 1.0;
  return UpperNormalTail((w_plus - mean - 0.5) / std::sqrt(variance));
}

double MannWhitneyPValue(const std::vector<double>& now, const std::vector<double>& reference) {
  if (now.empty() || reference.empty()) return 1.0;
  std::vector<double> pooled = now;
  pooled.insert(pooled.end(), reference.begin(), reference.end());
  double tie_term = 0.0;
  const std::vector<double> ranks = MidRanks(pooled, &tie_term);
  const double n1 = static_cast<double>(now.size());
  const double n2 = static_cast<double>(reference.size());
  const double rank_sum = std::accumulate(ranks.begin(), ranks.begin() + now.size(), 0.0);
  const double u = rank_sum - n1 * (n1 + 1.0) / 2.0;
  const double n = n1 + n2;
  const double variance = n1 * n2 / 12.0 * ((n + 1.0) - tie_term / (n * (n - 1.0)));
  if (variance <= 0.0) return 1.0;
  return UpperNormalTail((u - n1 * n2 / 2.0 - 0.5) / std::sqrt(variance));
}

std::vector<double> HolmAdjusted(const std::vector<double>& p) {
  std::vector<size_t> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return p[a] < p[b]; });
  std::vector<double> adjusted(p.size());
  double running = 0.0;
  for (size_t i = 0; i < order.size(); ++i) {
    const double scaled = static_cast<double>(p.size() - i) * p[order[i]];
    running = std::max(running, std::min(1.0, scaled));
    adjusted[order[i]] = running;
  }
  return adjusted;
}

}  // namespace markerbench
