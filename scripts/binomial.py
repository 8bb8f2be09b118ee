"""The binomial distribution's lower tail, exact, for the scripts' tests and intervals
(paired_runs.py's sign tests, speed_ratio.py's interval for a median, ci_power.py's power)."""
import math


def at_most(n, k, p=0.5):
    """P(B <= k) for B ~ binomial(n, p), summed term by term (0 for k < 0, 1 for k >= n)."""
    if k < 0:
        return 0.0
    if k >= n:
        return 1.0
    return sum(math.comb(n, i) * p**i * (1 - p) ** (n - i) for i in range(k + 1))


def at_least(n, k, p=0.5):
    """P(B >= k), as the lower tail of n - B ~ binomial(n, 1 - p) (no 1 - P(B < k), which loses
    a small tail to rounding)."""
    return at_most(n, n - k, 1 - p)


def two_sided_sign_p(n, k):
    """P of a split at least as uneven as k of n under a fair coin (exact, two-sided)."""
    if n == 0:
        return 1.0
    return min(1.0, 2 * at_most(n, min(k, n - k)))
