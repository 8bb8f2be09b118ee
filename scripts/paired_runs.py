#!/usr/bin/python3
"""Paired comparison of two scenarios run on the same frames (the same seed and poses; e.g.
scenarios/sequences/recede.yaml, tracked, and recede_each_frame.yaml, each frame alone).

Usage: paired_runs.py DIR SCENARIO_A SCENARIO_B [--min-distance M] [--out CSV]

Reads DIR/SCENARIO_A/frames.csv and DIR/SCENARIO_B/frames.csv (or their .zst), pairs their rows
by tracker, marker, trial and frame (every row must have its pair), keeps the frames at least M
metres from the marker (the true distance, `distance_m`), and writes per tracker and marker:
  frames                       the pairs kept;
  success_a, success_b         each scenario's success rate there (the first hypothesis within
                               10 % of the distance, the experiments' definition);
  only_a, only_b               the discordant frames: a success in one scenario only;
  mcnemar_p                    McNemar's exact two-sided p on them (frames as samples);
  videos, videos_a_better, videos_b_better
                               for sequence scenarios the trials (videos) with frames kept, and
                               those whose success rate is higher in A or in B;
  sign_p                       the exact two-sided sign test on the videos (the videos as
                               samples: a video's frames are not independent draws).
"""
import argparse
import csv
import io
import os
import subprocess
import sys

import binomial

SUCCESS_FRACTION = 0.1


def fail(message):
    """Bad input: the message on stderr, exit status 2 (README, "What markerbench promises")."""
    print(f"paired_runs: {message}", file=sys.stderr)
    sys.exit(2)


def read_frames(run_dir):
    path = os.path.join(run_dir, "frames.csv")
    if os.path.exists(path):
        with open(path, newline="") as f:
            return list(csv.DictReader(f))
    if os.path.exists(path + ".zst"):
        text = subprocess.run(["zstd", "-dc", path + ".zst"], check=True,
                              capture_output=True).stdout.decode()
        return list(csv.DictReader(io.StringIO(text)))
    fail(f"{path}: no such file (nor .zst); run the sweep first")


def success(row):
    error = row["position_error_m"]
    return error != "" and float(error) <= SUCCESS_FRACTION * float(row["distance_m"])


def compare(rows_a, rows_b, min_distance):
    """One dict per (tracker, marker), in order of appearance in A."""
    key = lambda r: (r["tracker"], r["marker"], r["trial"], r["frame"])
    b_by_key = {key(r): r for r in rows_b}
    if len(b_by_key) != len(rows_a) or any(key(r) not in b_by_key for r in rows_a):
        raise ValueError("the two runs do not hold the same frames")
    groups = {}
    for a in rows_a:
        b = b_by_key[key(a)]
        if a["distance_m"] != b["distance_m"]:
            raise ValueError(f"frame {key(a)}: distances {a['distance_m']} and "
                             f"{b['distance_m']}: not the same frames")
        if float(a["distance_m"]) < min_distance:
            continue
        g = groups.setdefault((a["tracker"], a["marker"]), {"pairs": [], "videos": {}})
        pair = (success(a), success(b))
        g["pairs"].append(pair)
        g["videos"].setdefault(a["trial"], []).append(pair)
    out = []
    for (tracker, marker), g in groups.items():
        pairs = g["pairs"]
        only_a = sum(1 for a, b in pairs if a and not b)
        only_b = sum(1 for a, b in pairs if b and not a)
        a_better = b_better = 0
        for video in g["videos"].values():
            difference = sum(a for a, _ in video) - sum(b for _, b in video)
            a_better += difference > 0
            b_better += difference < 0
        out.append({
            "tracker": tracker, "marker": marker, "frames": len(pairs),
            "success_a": sum(a for a, _ in pairs) / len(pairs),
            "success_b": sum(b for _, b in pairs) / len(pairs),
            "only_a": only_a, "only_b": only_b,
            "mcnemar_p": binomial.two_sided_sign_p(only_a + only_b, only_a),
            "videos": len(g["videos"]), "videos_a_better": a_better,
            "videos_b_better": b_better,
            "sign_p": binomial.two_sided_sign_p(a_better + b_better, a_better),
        })
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dir")
    parser.add_argument("scenario_a")
    parser.add_argument("scenario_b")
    parser.add_argument("--min-distance", type=float, default=0.0)
    parser.add_argument("--out", help="write the CSV here (else to stdout)")
    args = parser.parse_args()
    try:
        rows = compare(read_frames(os.path.join(args.dir, args.scenario_a)),
                       read_frames(os.path.join(args.dir, args.scenario_b)), args.min_distance)
    except (KeyError, ValueError) as e:
        fail(f"{args.dir}/{args.scenario_a}/frames.csv and {args.dir}/{args.scenario_b}/"
             f"frames.csv: {e}")
    columns = ["tracker", "marker", "frames", "success_a", "success_b", "only_a", "only_b",
               "mcnemar_p", "videos", "videos_a_better", "videos_b_better", "sign_p"]
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=columns, lineterminator="\n")
    writer.writeheader()
    for r in rows:
        writer.writerow({k: f"{v:.4g}" if isinstance(v, float) else v for k, v in r.items()})
    if args.out:
        with open(args.out + ".tmp", "w") as f:
            f.write(text.getvalue())
        os.replace(args.out + ".tmp", args.out)
    else:
        sys.stdout.write(text.getvalue())


if __name__ == "__main__":
    main()
