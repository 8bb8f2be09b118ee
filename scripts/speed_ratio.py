#!/usr/bin/env python3
"""Times Google Benchmark benchmarks against a reference in the same runs, as a paired ratio
with a 95 % interval (results/speed.md: speed goals are ratios to a reference measured in the
same run). On a shared VM a program's time drifts by 20-30 % between runs, more than most
changes one wants to see; a ratio to a reference timed beside it, run after run, cancels most
of that drift, and its median over the runs gets a distribution-free interval.

Each run invokes every benchmark once (a process each, `--benchmark_min_time`), in an order
rotated by one from run to run, so that each benchmark takes each place in the order equally
often. Per run, each benchmark's time over the reference's; over the runs, the median of those
ratios and its 95 % interval from the order statistics (the ranks a binomial(n, 1/2) gives;
6 runs at least). The table's first line names the machine (the CPU model of /proc/cpuinfo and
the CPUs seen): ratios to the same reference differ from one CPU model to another.

Usage:
  speed_ratio.py --reference PROGRAM:BENCHMARK --measure PROGRAM:BENCHMARK [--measure ...]
                 [--runs N] [--min-time SECONDS]
e.g. from the project root:
  scripts/speed_ratio.py --reference build/trackers/apriltag_benchmark:BM_AprilTag \\
      --measure build/trackers/circle_tracker_benchmark:BM_CircleFullDetection
A benchmark is named as Google Benchmark prints it. Prints a Markdown table; exit status 2
with a message naming the program and the benchmark on bad input or a benchmark that fails.
"""
import argparse
import json
import os
import re
import statistics
import subprocess
import sys

import binomial

MIN_RUNS = 6
MS_PER_UNIT = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


class SpeedRatioError(Exception):
    pass


def parse_spec(spec):
    """PROGRAM:BENCHMARK (the benchmark after the last colon)."""
    program, sep, benchmark = spec.rpartition(":")
    if not sep or not program or not benchmark:
        raise SpeedRatioError(f"{spec!r}: expected PROGRAM:BENCHMARK")
    if not (os.path.isfile(program) and os.access(program, os.X_OK)):
        raise SpeedRatioError(f"{program}: no such executable (in {spec!r})")
    return program, benchmark


def time_ms(program, benchmark, min_time):
    """One invocation's real time per iteration of `benchmark`, in ms."""
    command = [program, f"--benchmark_filter=^{re.escape(benchmark)}$",
               f"--benchmark_min_time={min_time}", "--benchmark_format=json"]
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    where = f"{program}:{benchmark}"
    if done.returncode != 0:
        raise SpeedRatioError(f"{where}: exit status {done.returncode}: "
                              f"{done.stderr.strip()[-300:]}")
    try:
        results = json.loads(done.stdout)["benchmarks"]
    except (json.JSONDecodeError, KeyError) as error:
        raise SpeedRatioError(f"{where}: no benchmark JSON on standard output ({error})")
    runs = [r for r in results if r.get("name") == benchmark and r.get("run_type") != "aggregate"]
    if not runs:
        raise SpeedRatioError(f"{where}: the program has no benchmark of that name")
    run = runs[0]
    if run.get("error_occurred"):
        raise SpeedRatioError(f"{where}: {run.get('error_message', 'error')}")
    unit = run.get("time_unit", "ns")
    if unit not in MS_PER_UNIT:
        raise SpeedRatioError(f"{where}: unknown time_unit {unit!r}")
    return run["real_time"] * MS_PER_UNIT[unit]


def machine(cpuinfo="/proc/cpuinfo"):
    """The CPU model (the first "model name" of `cpuinfo`) and how many CPUs it lists, e.g.
    "AMD EPYC, 2 CPUs"; "an unknown CPU" where the file cannot be read or names none."""
    try:
        with open(cpuinfo) as f:
            lines = f.read().splitlines()
    except OSError:
        return "an unknown CPU"
    models = [line.partition(":")[2].strip() for line in lines if line.startswith("model name")]
    if not models or not models[0]:
        return "an unknown CPU"
    return f"{models[0]}, {len(models)} CPU{'s' if len(models) > 1 else ''}"


def median_interval(values, confidence=0.95):
    """The sample median and a distribution-free interval for the median: the order
    statistics x_(k), x_(n+1-k) (1-based) with k the largest rank whose binomial(n, 1/2)
    tail P(B < k) is at most (1 - confidence)/2."""
    n = len(values)
    ordered = sorted(values)
    k = 0
    while binomial.at_most(n, k) <= (1.0 - confidence) / 2.0:
        k += 1
    if k == 0:
        raise SpeedRatioError(f"{n} runs give no {confidence:.0%} interval: {MIN_RUNS} at least")
    return statistics.median(ordered), ordered[k - 1], ordered[n - k]


def measure(reference, measured, runs, min_time, log=sys.stderr):
    """Per benchmark (the reference first): its times and its ratios to the reference, run
    by run."""
    specs = [reference] + measured
    times = [[] for _ in specs]
    for run in range(runs):
        order = [(run + i) % len(specs) for i in range(len(specs))]
        for i in order:
            times[i].append(time_ms(*specs[i], min_time))
        print(f"run {run + 1}/{runs}: " +
              ", ".join(f"{specs[i][1]} {times[i][-1]:.3f} ms" for i in range(len(specs))),
              file=log)
    ratios = [[t / r for t, r in zip(times[i], times[0])] for i in range(len(specs))]
    return times, ratios


def main(argv=None, cpuinfo="/proc/cpuinfo"):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--reference", required=True, help="PROGRAM:BENCHMARK")
    parser.add_argument("--measure", action="append", required=True, help="PROGRAM:BENCHMARK")
    parser.add_argument("--runs", type=int, default=15)
    parser.add_argument("--min-time", type=float, default=0.3,
                        help="--benchmark_min_time of each invocation (s)")
    args = parser.parse_args(argv)
    try:
        if args.runs < MIN_RUNS:
            raise SpeedRatioError(f"--runs {args.runs}: {MIN_RUNS} at least (a 95 % interval)")
        if not args.min_time > 0.0:
            raise SpeedRatioError(f"--min-time {args.min_time}: must be > 0")
        reference = parse_spec(args.reference)
        measured = [parse_spec(spec) for spec in args.measure]
        times, ratios = measure(reference, measured, args.runs, args.min_time)
        specs = [reference] + measured
        print(f"{args.runs} runs, each benchmark {args.min_time} s a run, in rotated order; "
              f"ratios to `{reference[1]}` in the same run; on {machine(cpuinfo)}")
        print()
        print("| benchmark | median time (ms) | ratio to the reference: median | 95 % interval |")
        print("|---|---|---|---|")
        for i, (program, benchmark) in enumerate(specs):
            if i == 0:
                print(f"| `{benchmark}` (reference) | {statistics.median(times[0]):.3f} | 1 | |")
                continue
            middle, low, high = median_interval(ratios[i])
            print(f"| `{benchmark}` | {statistics.median(times[i]):.3f} | {middle:.3f} | "
                  f"{low:.3f}-{high:.3f} |")
    except SpeedRatioError as error:
        print(f"speed_ratio: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
