// One-sided significance tests for comparing a run with a reference (markerbench check).
// Each returns the p-value of the alternative "worse": the first argument tends to be larger,
// or the reference-only successes outnumber the new ones.
#pragma once

#include <vector>

namespace markerbench {

// Exact McNemar test on paired successes: `lost` frames succeeded in the reference and fail
// now, `gained` the reverse. p = P(X >= lost), X ~ Binomial(lost + gained, 1/2).
double McNemarPValue(int lost, int gained);

// Wilcoxon signed-rank test that the paired `differences` (now minus reference) lean
// positive. Zeros are dropped (Wilcoxon's convention) and ties get mid-ranks. Exact
// permutation distribution for up to kExactSignedRankMax non-zero differences, else the
// normal approximation with tie and continuity corrections.
inline constexpr int kExactSignedRankMax = 100;
double WilcoxonSignedRankPValue(const std::vector<double>& differences);

// Mann-Whitney U test that `now` tends to be larger than `reference` (independent samples),
// by the normal approximation with tie and continuity corrections; 1 when a sample is empty.
double MannWhitneyPValue(const std::vector<double>& now, const std::vector<double>& reference);

// Holm's step-down adjustment of a family of p-values (strong control of the family-wise
// error): reject p_adjusted[i] < alpha. Same order as `p`.
std::vector<double> HolmAdjusted(const std::vector<double>& p);

}  // namespace markerbench
