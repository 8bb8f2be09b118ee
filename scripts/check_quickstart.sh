#!/usr/bin/env bash
# Runs the README's quick start (the code block after "Then, with `mb=...`") as written, with
# mb the binary under test and /tmp/ replaced by a fresh folder, so that the README's first
# commands stay true. Exit 1 when one fails.
#   check_quickstart.sh MARKERBENCH_BINARY
set -euo pipefail
binary=$(realpath "${1:?usage: check_quickstart.sh MARKERBENCH_BINARY}")
root=$(realpath "$(dirname "$0")/..")
work=$(mktemp -d /tmp/markerbench_quickstart.XXXXXX)
trap 'rm -rf "$work"' EXIT
commands=$(awk '/^Then, with `mb=/ {found = 1; next}
                found && /^```sh/ {inside = 1; next}
                inside && /^```/ {exit}
                inside {print}' "$root/README.md")
if [ -z "$commands" ]; then
  echo "check_quickstart: no quick start block found in README.md" >&2
  exit 1
fi
cd "$root"
mb=$binary bash -euo pipefail -c "${commands//\/tmp\//$work/}" > "$work.log" 2>&1 || {
  cat "$work.log" >&2
  rm -f "$work.log"
  echo "check_quickstart: the README's quick start failed" >&2
  exit 1
}
rm -f "$work.log"
echo "check_quickstart: $(grep -c '^\$mb' <<< "$commands") commands ran"
