#!/usr/bin/env python3
"""The architecture's layers, checked on the sources: core includes only core; renderer only
core and renderer; trackers only core and trackers (trackers never see the renderer);
testing (the test support library) core, renderer, trackers and testing; bench anything.
Test, benchmark and fuzz programs are exempt: they render frames to test trackers on, through
testing/. Exit 1 listing every include across a layer.

    check_layers.py [SOURCE_ROOT]
"""
import pathlib
import re
import sys

ALLOWED = {
    "core": {"core"},
    "renderer": {"core", "renderer"},
    "trackers": {"core", "trackers"},
    "testing": {"core", "renderer", "trackers", "testing"},
}
EXEMPT = re.compile(r"(_test\.cc|_benchmark\.cc|_fuzz\.cc)$")
INCLUDE = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/')


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
                if match and match.group(1) in ALLOWED and match.group(1) not in allowed:
                    problems.append(f"{path.relative_to(root)}:{number}: {layer} includes "
                                    f"{match.group(1)}/ ({line.strip()})")
    if problems:
        print("\n".join(problems), file=sys.stderr)
        sys.exit(1)
    print(f"check_layers: {checked} sources keep to their layers")


if __name__ == "__main__":
    main()
