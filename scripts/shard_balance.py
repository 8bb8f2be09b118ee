#!/usr/bin/env python3
"""How evenly `sweep --shard I/N` spreads a sweep's work (results/speed.md): from a run's
frames.csv and timing.csv, the trackers' time per pose group (cell, trial), summed per
shard under the interleaved split markerbench uses (group mod N) and under contiguous blocks
of the plan, for several N. Reported: the slowest shard's time over the mean shard's; 1.00
is a perfect split, and the whole job waits for the slowest shard.

    shard_balance.py RUN_DIR/SCENARIO [N...]      (default N: 2 4 8 16)
"""
import csv
import os
import sys


def group_costs(folder):
    """Tracker milliseconds per pose group, in plan order."""
    with open(os.path.join(folder, "frames.csv"), newline="") as f:
        frames = list(csv.DictReader(f))
    with open(os.path.join(folder, "timing.csv"), newline="") as f:
        times = [float(row["time_ms"]) for row in csv.DictReader(f)]
    if len(frames) != len(times):
        sys.exit(f"shard_balance: {folder}: frames.csv and timing.csv differ in length")
    cells = []  # (grid combination, sweep value) in plan order
    costs = {}
    for row, time_ms in zip(frames, times):
        cell = (row.get("grid", ""), row["sweep_value"])
        if cell not in cells:
            cells.append(cell)
        key = (cells.index(cell), int(row["trial"]))
        costs[key] = costs.get(key, 0.0) + time_ms
    return [costs[key] for key in sorted(costs)], len(cells)


def imbalance(loads):
    return max(loads) / (sum(loads) / len(loads))


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    folder = sys.argv[1]
    counts = [int(n) for n in sys.argv[2:]] or [2, 4, 8, 16]
    costs, cells = group_costs(folder)
    groups = len(costs)
    print(f"{os.path.basename(folder.rstrip('/'))}: {groups} pose groups over {cells} cells, "
          f"{sum(costs) / 1000:.1f} s of tracker time")
    print()
    print("| N | interleaved (markerbench) | blocks |")
    print("|---|---|---|")
    for n in counts:
        interleaved = [sum(costs[g] for g in range(i, groups, n)) for i in range(n)]
        bounds = [round(i * groups / n) for i in range(n + 1)]
        blocks = [sum(costs[bounds[i]:bounds[i + 1]]) for i in range(n)]
        print(f"| {n} | {imbalance(interleaved):.2f} | {imbalance(blocks):.2f} |")


if __name__ == "__main__":
    main()
