#!/usr/bin/env python3
"""Where a program's time goes, in instructions: each stage's share of a function's calls,
counted by Callgrind (valgrind). Instruction counts do not drift with the machine's load as
times do (results/speed.md), so two builds' counts tell apart changes far below what a timed
comparison resolves; they stand for time only where the code is bound by its instructions, not
its memory, so a speed claim still takes `speed_ratio.py`.

Runs COMMAND under Callgrind, then reads PER's inclusive count and calls (e.g. the tracker's
Track call; `callgrind_annotate --inclusive=yes`, without and with `--tree=caller`) and each
stage's inclusive count, as shares of PER's. Counts are of the whole run (Callgrind counts no
call into a function it is told to count inside, `--toggle-collect`, so PER's calls would be
unknown): name stages that COMMAND runs inside PER alone, not in its set-up. A Google Benchmark
program sets its iterations from the time, and so which of its frames are counted; a sweep
(`markerbench sweep`, one thread) counts the same frames in every build, for an A/B of two
builds. A stage is the one function whose name begins with its pattern (else contains it),
leaving out what is defined inside that function (its lambdas, whose counts its own includes); a
pattern that matches none, or several, is an error. A function called inside another stage is
counted in both.

Usage:
  instruction_shares.py --per FUNCTION --stage LABEL=PATTERN [--stage ...] -- COMMAND [ARG ...]
e.g. from the project root:
  scripts/instruction_shares.py \\
      --per 'markerbench::CircleTracker::Track(markerbench::Observation const&)' \\
      --stage 'fit on the pixels=markerbench::RefinePhotometricFromStarts(' \\
      -- build/trackers/circle_tracker_benchmark --benchmark_filter='^BM_CircleFullDetection$'
Prints a Markdown table; exit status 2 with a message naming the command or the stage on bad
input, a missing valgrind, or a run that fails.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys
import tempfile

# A function's line of callgrind_annotate: its count, its share, and file:function, then the
# object file in brackets, e.g. "1,371,324,016 (54.35%)  ???:ns::f(int) [/path/prog]".
FUNCTION_LINE = re.compile(r"^\s*([\d,]+)\s+\(\s*[\d.]+%\)\s+(<\s+|\*\s+|>\s+)?(.*)$")
CALLS = re.compile(r"\((\d[\d,]*)x\)")


class InstructionSharesError(Exception):
    pass


def function_name(located):
    """The function of "file:function [object]" (file names hold no colon; ??? without debug
    information)."""
    located = re.sub(r"\s+\[/[^\]]*\]\s*$", "", located)
    located = CALLS.sub("", located).rstrip()
    _, _, name = located.partition(":")
    return name


def inclusive_counts(annotated):
    """Each function's inclusive count from `callgrind_annotate --inclusive=yes` output: the
    largest of its lines (a build with debug information lists a function whole, and again in
    parts by the source files its code comes from, its own and the headers inlined into it)."""
    counts = {}
    for line in annotated.splitlines():
        match = FUNCTION_LINE.match(line)
        if not match or match.group(2) or "PROGRAM TOTALS" in line:
            continue
        name = function_name(match.group(3))
        if name:
            counts[name] = max(counts.get(name, 0), int(match.group(1).replace(",", "")))
    return counts


def calls_of(tree, function):
    """How many times `function` was called: its callers' call counts, the "<" lines of its
    blocks in `callgrind_annotate --inclusive=yes --tree=caller` output. Inclusive: a build with
    debug information lists a function once per source file its code comes from, and its callers
    under an entry that may count no instruction of its own, which a tree of self counts leaves
    out (so none of its calls were counted)."""
    calls, callers = 0, []
    for line in tree.splitlines():
        match = FUNCTION_LINE.match(line)
        if not match:
            callers = []
            continue
        arrow = (match.group(2) or "").strip()
        if arrow == "<":
            found = CALLS.search(match.group(3))
            callers.append(int(found.group(1).replace(",", "")) if found else 0)
        elif arrow == "*":
            if function_name(match.group(3)) == function:
                calls += sum(callers)
            callers = []
    return calls


def parse_stage(spec):
    label, sep, pattern = spec.partition("=")
    if not sep or not label or not pattern:
        raise InstructionSharesError(f"--stage {spec!r}: expected LABEL=PATTERN")
    return label, pattern


def the_function(counts, pattern, what):
    matches = [name for name in counts if name.startswith(pattern)]
    if not matches:
        matches = [name for name in counts if pattern in name]
    # Not what is defined inside another match, whose name begins with that match's.
    matches = sorted(name for name in matches
                     if not any(other != name and name.startswith(other) for other in matches))
    if not matches:
        raise InstructionSharesError(f"{what} {pattern!r}: no function counted has it in its name")
    if len(matches) > 1:
        listed = "; ".join(matches[:5]) + ("; ..." if len(matches) > 5 else "")
        raise InstructionSharesError(
            f"{what} {pattern!r}: {len(matches)} functions have it in their names ({listed}): "
            "name one")
    return matches[0]


def run(command, what):
    try:
        done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    except FileNotFoundError:
        raise InstructionSharesError(
            f"{command[0]}: not installed (valgrind, from scripts/install-deps.sh)")
    if done.returncode != 0:
        raise InstructionSharesError(
            f"{what}: exit status {done.returncode}: {done.stderr.strip()[-300:]}")
    return done.stdout


def shares(command, per, stages):
    """PER's calls, its count per call, and each stage's (label, function, count)."""
    if not command:
        raise InstructionSharesError("no command: give it after --")
    if not shutil.which(command[0]):
        raise InstructionSharesError(f"{command[0]}: no such executable")
    shown = " ".join(command)
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "callgrind.out")
        run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}"] + command,
            f"{shown} under callgrind")
        if not os.path.exists(out):
            raise InstructionSharesError(f"{shown}: callgrind wrote no profile")
        counts = inclusive_counts(
            run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out],
                "callgrind_annotate"))
        tree = run(["callgrind_annotate", "--inclusive=yes", "--tree=caller", "--threshold=100",
                    out], "callgrind_annotate")
    if per not in counts:
        raise InstructionSharesError(
            f"--per {per!r}: not called in {shown} (or not its exact name)")
    calls = calls_of(tree, per)
    if calls == 0:
        raise InstructionSharesError(f"--per {per!r}: no calls counted")
    rows = []
    for label, pattern in stages:
        name = the_function(counts, pattern, f"--stage {label!r}:")
        rows.append((label, name, counts[name]))
    return calls, counts[per], rows


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--per", required=True, help="the function whose calls are counted")
    parser.add_argument("--stage", action="append", default=[], help="LABEL=PATTERN")
    parser.add_argument("command", nargs=argparse.REMAINDER, help="-- COMMAND [ARG ...]")
    args = parser.parse_args(argv)
    command = args.command[1:] if args.command[:1] == ["--"] else args.command
    try:
        stages = [parse_stage(spec) for spec in args.stage]
        calls, total, rows = shares(command, args.per, stages)
        print(f"`{' '.join(command)}`: {calls} calls of `{args.per}`, "
              f"{total / calls / 1e6:.3f} M instructions a call")
        print()
        print("| stage | function | M instructions a call | share |")
        print("|---|---|---|---|")
        for label, name, count in rows:
            print(f"| {label} | `{name}` | {count / calls / 1e6:.3f} | {count / total:.1%} |")
    except InstructionSharesError as error:
        print(f"instruction_shares: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
