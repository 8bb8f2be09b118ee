#!/usr/bin/env python3
"""Peak memory and time of `report` and `merge` on large synthetic runs (results/speed.md).

The rows are a real sweep's (results/reference/ci_noise: 4,000 rows, two sweep values of
2,000 rows), copied with new frame numbers and sweep values until the file has ROWS rows; each
copy is two new cells, so a cell stays 2,000 rows however large the file grows. The run is also cut into 4
shards (frames dealt out by number), which `merge` puts back together; the merged file must
equal the whole one byte for byte.

    streaming_memory.py BINARY ROWS [ROWS...]     a Markdown table, one line per ROWS
    streaming_memory.py BINARY --check            fails unless peak memory is flat from
                                                  50,000 to 400,000 rows (ctest)
Work files go to a temporary folder under $TMPDIR (10 million rows: about 14 GB).
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
TEMPLATE = os.path.join(ROOT, "results", "reference", "ci_noise")
SHARDS = 4


def read_template():
    with open(os.path.join(TEMPLATE, "frames.csv")) as f:
        frames = f.read().splitlines()
    with open(os.path.join(TEMPLATE, "timing.csv")) as f:
        timing = f.read().splitlines()
    return frames[0], frames[1:], timing[0], timing[1:]


def generate(folder, rows):
    """folder/whole/big (the run) and folder/shard-I/big (its shards)."""
    frames_header, frames, timing_header, timing = read_template()
    span = 1 + max(int(line.split(",", 5)[4]) for line in frames)
    names = ["whole"] + [f"shard-{i}" for i in range(SHARDS)]
    outputs = {}
    for name in names:
        os.makedirs(os.path.join(folder, name, "big"))
        outputs[name] = (open(os.path.join(folder, name, "big", "frames.csv"), "w"),
                         open(os.path.join(folder, name, "big", "timing.csv"), "w"))
        outputs[name][0].write(frames_header + "\n")
        outputs[name][1].write(timing_header + "\n")
    counts = [0] * SHARDS
    written = 0
    copy = 0
    while written < rows:
        for frame_line, timing_line in zip(frames, timing):
            if written == rows:
                break
            f = frame_line.split(",", 5)
            frame = copy * span + int(f[4])
            f[2] = repr(copy + float(f[2]))  # sweep values in [0, 1): every copy new cells
            f[4] = str(frame)
            t = timing_line.split(",", 1)
            row = ",".join(f) + "\n"
            timing_row = str(frame) + "," + t[1] + "\n"
            shard = frame % SHARDS
            for name in ("whole", f"shard-{shard}"):
                outputs[name][0].write(row)
                outputs[name][1].write(timing_row)
            counts[shard] += 1
            written += 1
        copy += 1
    for name in names:
        for handle in outputs[name]:
            handle.close()
    for i in range(SHARDS):
        run = {"fingerprint": "synthetic", "shard": {"index": i, "count": SHARDS},
               "complete": True, "rows": counts[i]}
        with open(os.path.join(folder, f"shard-{i}", "big", "run.json"), "w") as f:
            json.dump(run, f)


def measure(args):
    """(seconds, peak resident set in MB) of one command."""
    start = time.monotonic()
    process = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(process.pid, 0)
    seconds = time.monotonic() - start
    error = process.stderr.read().decode()
    process.stderr.close()
    if status != 0:
        sys.exit(f"streaming_memory: {' '.join(args)} failed: {error}")
    return seconds, usage.ru_maxrss / 1024.0


def same_file(a, b):
    return subprocess.run(["cmp", "-s", a, b]).returncode == 0


def run(binary, rows):
    folder = tempfile.mkdtemp(prefix="markerbench_streaming.")
    try:
        generate(folder, rows)
        whole = os.path.join(folder, "whole")
        shards = [os.path.join(folder, f"shard-{i}") for i in range(SHARDS)]
        result = {"rows": rows,
                  "size_mb": os.path.getsize(os.path.join(whole, "big", "frames.csv")) / 1e6}
        result["report"] = measure([binary, "report", whole, "--no-plots"])
        merged = os.path.join(folder, "merged")
        result["merge"] = measure([binary, "merge", *shards, "--out", merged])
        if not same_file(os.path.join(merged, "big", "frames.csv"),
                         os.path.join(whole, "big", "frames.csv")):
            sys.exit("streaming_memory: the merged frames.csv differs from the whole run's")
        packed = os.path.join(folder, "packed")
        result["merge_zstd"] = measure([binary, "merge", *shards, "--out", packed, "--zstd"])
        result["zstd_mb"] = os.path.getsize(os.path.join(packed, "big", "frames.csv.zst")) / 1e6
        result["report_zstd"] = measure([binary, "report", packed, "--no-plots"])
        if not same_file(os.path.join(packed, "summary.csv"), os.path.join(whole, "summary.csv")):
            sys.exit("streaming_memory: summary.csv of the compressed run differs")
        return result
    finally:
        shutil.rmtree(folder)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    binary = os.path.abspath(sys.argv[1])
    if sys.argv[2] == "--check":
        small, large = run(binary, 50_000), run(binary, 400_000)
        for step in ("report", "merge", "merge_zstd", "report_zstd"):
            growth = large[step][1] - small[step][1]
            print(f"{step}: peak {small[step][1]:.1f} MB at 50,000 rows, "
                  f"{large[step][1]:.1f} MB at 400,000 rows")
            # 350,000 more rows would be about 250 MB if the rows were kept.
            if growth > 8.0:
                sys.exit(f"streaming_memory: {step}'s peak memory grew by {growth:.1f} MB")
        return
    print("| rows | frames.csv | report: time, peak RSS | merge 4 shards | merge --zstd "
          "(frames.csv.zst) | report on .zst |")
    print("|---|---|---|---|---|---|")
    for rows in (int(text) for text in sys.argv[2:]):
        r = run(binary, rows)
        cell = lambda step: f"{r[step][0]:.1f} s, {r[step][1]:.0f} MB"
        print(f"| {rows:,} | {r['size_mb']:,.0f} MB | {cell('report')} | {cell('merge')} | "
              f"{cell('merge_zstd')} ({r['zstd_mb']:,.0f} MB) | {cell('report_zstd')} |",
              flush=True)


if __name__ == "__main__":
    main()
