// The upper tail of a fair coin's binomial distribution: the exact p-value of a sign test or
// of McNemar's test on the discordant pairs.
#pragma once

namespace markerbench {

// P(X >= k) for X ~ Binomial(n, 1/2); 1 for k <= 0, 0 for k > n. Summed in logs, so it stays
// finite for any n.
double FairBinomialUpperTail(int n, int k);

}  // namespace markerbench
