#!/usr/bin/env python3
"""The architecture's layers, checked on the sources: core includes only core; renderer only
core and renderer; trackers only core and trackers (trackers never see the renderer);
testing (the test support library) core, renderer, trackers and testing. bench's rooms follow
the data flow: io and metrics include only core (and themselves); plan io and the lower
layers; run plan, metrics and io; report run, plan (a scenario's trajectory), metrics and io;
cli anything. Test, benchmark and fuzz programs are exempt: they render frames to test
trackers on, through testing/.
Exit 1 listing every include across a layer.

    check_layers.py [SOURCE_ROOT]
"""
import pathlib
import re
import sys

LOWER = {"core", "renderer", "trackers"}
ALLOWED = {
    "core": {"core"},
    "renderer": {"core", "renderer"},
    "trackers": {"core", "trackers"},
    "testing": {"core", "renderer", "trackers", "testing"},
    "bench/io": {"core", "bench/io"},
    "bench/metrics": {"core", "bench/metrics"},
    "bench/plan": LOWER | {"bench/io", "bench/plan"},
    "bench/run": LOWER | {"bench/io", "bench/metrics", "bench/plan", "bench/run"},
    "bench/report": LOWER | {"bench/io", "bench/metrics", "bench/plan", "bench/run", "bench/report"},
}
TOP = {"core", "renderer", "trackers", "testing", "bench"}
EXEMPT = re.compile(r"(_test\.cc|_benchmark\.cc|_fuzz\.cc)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/(?:([a-z_]+)/)?')


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
    problems = []
    checked = 0
    for layer, allowed in ALLOWED.items():
        for path in sorted((root / layer).rglob("*")):
            if path.suffix not in (".h", ".cc") or EXEMPT.search(path.name):
                continue
            checked += 1
            for number, line in enumerate(path.read_text().splitlines(), 1):
                match = INCLUDE.match(line)
                if not match:
                    continue
                # bench/<room>/x.h is in layer bench/<room>; other paths in their top folder.
                target = match.group(1)
                if target == "bench" and match.group(2):
                    target += "/" + match.group(2)
                if target.split("/")[0] in TOP and target not in allowed:
                    problems.append(f"{path.relative_to(root)}:{number}: {layer} includes "
                                    f"{target}/ ({line.strip()})")
    if problems:
        print("\n".join(problems), file=sys.stderr)
        sys.exit(1)
    print(f"check_layers: {checked} sources keep to their layers")


if __name__ == "__main__":
    main()
