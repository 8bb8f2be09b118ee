#!/usr/bin/python3
"""Power of `markerbench check` on the CI suite (README, "Use markerbench as a regression gate").

For one regressed cell among all the suite's tests (Holm at alpha: the smallest p-value must
beat alpha / tests), the chance that check reports it:
  * success: the change loses `--success-drop` of the frames and gains none; the exact
    one-sided McNemar test then needs b lost frames with 0.5^b <= alpha / tests;
  * errors: per-frame log ratios now/reference ~ N(log(ratio), s^2), s measured on the
    reference as the within-cell spread of log(apriltag / apriltag-ippe) errors (two pose
    solvers on the same detections: a change to one stage of a tracker), Wilcoxon
    signed-rank (normal approximation) by simulation; it must also show a median ratio
    above 1 + min_effect.
Usage: scripts/ci_power.py [--reference results/reference] [--trials 200] ...
"""
import argparse
import csv
import glob
import math
import os
from collections import defaultdict

import numpy as np

import binomial


def log_ratio_spread(reference):
    """Median within-cell sd of log(apriltag / apriltag-ippe) position errors."""
    spreads = []
    for path in sorted(glob.glob(os.path.join(reference, "*", "frames.csv"))):
        cells = defaultdict(dict)
        for r in csv.DictReader(open(path)):
            if r["status"] == "ok" and r["tracker"] in ("apriltag", "apriltag-ippe"):
                cells[(r["sweep_value"], r["trial"])][r["tracker"]] = float(r["position_error_m"])
        by_value = defaultdict(list)
        for (value, _), e in cells.items():
            if len(e) == 2 and min(e.values()) > 0:
                by_value[value].append(math.log(e["apriltag"] / e["apriltag-ippe"]))
        spreads += [np.std(v) for v in by_value.values() if len(v) >= 20]
    return float(np.median(spreads)), len(spreads)


def wilcoxon_power(pairs, ratio, spread, threshold, min_effect, runs, rng):
    mean = pairs * (pairs + 1) / 4
    sd = math.sqrt(pairs * (pairs + 1) * (2 * pairs + 1) / 24)
    z_needed = math.sqrt(2) * erfcinv(2 * threshold)
    detected = 0
    for _ in range(runs):
        d = rng.normal(math.log(ratio), spread, pairs)
        ranks = np.argsort(np.argsort(np.abs(d))) + 1
        w_plus = ranks[d > 0].sum()
        z = (w_plus - mean - 0.5) / sd
        # The ratio of medians of errors scaled by exp(d) is about exp(median d).
        detected += z >= z_needed and math.exp(np.median(d)) > 1 + min_effect
    return detected / runs


def erfcinv(y):
    lo, hi = -10.0, 10.0  # erfc is decreasing
    for _ in range(200):
        mid = (lo + hi) / 2
        if math.erfc(mid) > y:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--reference", default="results/reference")
    parser.add_argument("--trials", type=int, default=200)
    parser.add_argument("--cells", type=int, default=77,
                        help="3 sweeps x 2 values x 11 series, e and f under noise (2 values), "
                        "the low-noise cell, 5 gamma cells and the wide lens's")
    parser.add_argument("--alpha", type=float, default=0.01)
    parser.add_argument("--success-drop", type=float, default=0.10)
    parser.add_argument("--error-ratio", type=float, default=1.25)
    parser.add_argument("--found", type=float, default=0.9, help="frames succeeding in both")
    parser.add_argument("--min-effect", type=float, default=0.10)
    parser.add_argument("--spread", type=float, help="log-ratio sd (default: measured)")
    args = parser.parse_args()
    tests = 3 * args.cells
    threshold = args.alpha / tests
    lost_needed = math.ceil(math.log(threshold) / math.log(0.5))
    success_power = binomial.at_least(args.trials, lost_needed, args.success_drop)
    spread, cells = log_ratio_spread(args.reference)
    if args.spread is not None:
        spread, cells = args.spread, 0
    pairs = int(args.trials * args.found)
    error_power = wilcoxon_power(pairs, args.error_ratio, spread, threshold, args.min_effect,
                                 4000, np.random.default_rng(1))
    print(f"{tests} tests, Holm's first threshold alpha/tests = {threshold:.2e}")
    print(f"success: {args.trials} paired frames, a {100 * args.success_drop:.0f}-point loss, "
          f"needs >= {lost_needed} lost frames: power {success_power:.3f}")
    print(f"errors: {pairs} frames succeeding in both, median ratio {args.error_ratio}, "
          f"log-ratio sd {spread:.2f} (median of {cells} cells): power {error_power:.3f}")


if __name__ == "__main__":
    main()
