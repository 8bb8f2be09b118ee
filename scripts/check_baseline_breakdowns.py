#!/usr/bin/env python3
"""Pins the baselines' breakdowns (issue 17): sweeps a short version of the paper's three
sweeps (scenarios/paper/, --trials N) with the trackers of scenarios/paper/breakdowns.yaml
and fails unless each breakdown is within one sweep step of the pinned one. A breakdown is
the report's (breakdowns.csv): the first sweep value with success below 50 % (success: a
pose within 10 % of the distance); "none" when success never drops below 50 %.

Usage: check_baseline_breakdowns.py MARKERBENCH [--trials N]
"""
import argparse
import csv
import pathlib
import subprocess
import sys
import tempfile

import yaml

ROOT = pathlib.Path(__file__).resolve().parent.parent
PINS = ROOT / "scenarios/paper/breakdowns.yaml"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("markerbench")
    parser.add_argument("--trials", type=int, default=16)
    args = parser.parse_args()
    pins = yaml.safe_load(PINS.read_text())["breakdowns"]
    scenarios = sorted({s for per in pins.values() for s in per})
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp) / "run"
        subprocess.run([args.markerbench, "sweep",
                        *[str(ROOT / f"scenarios/paper/{s}.yaml") for s in scenarios],
                        "--trials", str(args.trials), "--trackers", ",".join(pins),
                        "--out", str(out)], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        subprocess.run([args.markerbench, "report", str(out)], check=True,
                       stdout=subprocess.DEVNULL)
        rows = list(csv.DictReader(open(out / "summary.csv")))
        breakdowns = list(csv.DictReader(open(out / "breakdowns.csv")))
    failures = 0
    for tracker, per in pins.items():
        for scenario, pinned in per.items():
            values = sorted({float(r["sweep_value"]) for r in rows
                             if r["scenario"] == scenario and r["tracker"] == tracker})
            (mine,) = [r for r in breakdowns if r["scenario"] == scenario and r["tracker"] == tracker]
            found = mine["breakdown_value"] or "none"
            index = len(values) if found == "none" else values.index(float(found))
            pinned_index = len(values) if pinned == "none" else values.index(float(pinned))
            ok = abs(index - pinned_index) <= 1
            failures += not ok
            print(f"{'ok  ' if ok else 'FAIL'} {tracker} {scenario}: breakdown {found}, "
                  f"pinned {pinned}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
