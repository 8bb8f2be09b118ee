#!/usr/bin/env bash
# ctest install/package: builds the .deb with CPack, unpacks it into a temporary prefix (no
# root needed, nothing installed on this machine) and runs the smoke sweep and its report
# from there, in a folder outside the source tree. The installed binary must hold no path of
# the source tree: its data comes from PREFIX/share/markerbench.
# Usage: check_package.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
source_dir=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if ! (cd "$build" && cpack -G DEB -B "$work/package" > "$work/cpack.log" 2>&1); then
  cat "$work/cpack.log"
  exit 1
fi
deb=$(ls "$work"/package/markerbench_*.deb)
dpkg-deb --field "$deb" Depends | tee "$work/depends.txt"
grep -q "python3-matplotlib" "$work/depends.txt"
grep -q "libopencv" "$work/depends.txt"  # found by dpkg-shlibdeps
dpkg-deb -x "$deb" "$work/root"

mb="$work/root/usr/bin/markerbench"
if strings "$mb" | grep -qF "$source_dir"; then
  echo "check_package: the installed binary names the source tree $source_dir" >&2
  exit 1
fi
for file in share/markerbench/scenarios/smoke.yaml share/markerbench/scenarios/markers/circles_a.yaml \
  share/markerbench/scripts/plot_sweep.py share/doc/markerbench/README.md; do
  test -f "$work/root/usr/$file" || { echo "check_package: $file is not in the package" >&2; exit 1; }
done

cd "$work"
"$mb" --version
"$mb" list markers | grep -q "^Marker files in $work/root/usr/share/markerbench/scenarios/markers"
"$mb" sweep "$work/root/usr/share/markerbench/scenarios/smoke.yaml" --out run --threads 2
"$mb" report run
for file in run/smoke/frames.csv run/summary.csv run/report.md run/report.html run/smoke.png; do
  test -s "$file" || { echo "check_package: the installed binary wrote no $file" >&2; exit 1; }
done
echo "check_package: $(basename "$deb") installs and runs the smoke sweep"
