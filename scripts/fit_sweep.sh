#!/bin/bash
# The fit on every CGAL demo mesh (up to MAX_TRIANGLES control triangles,
# 10 000 by default), as a user would first run it:
#   loopsurf fit FILE --repair --hard-angle 30
# at the default resolution and tolerance, one thread, 90 s each, one
# markdown row per mesh: whether the fit met the tolerance and its worst
# distance to the input's vertices (or the miss it was refused for), its
# worst distance to the input's edge midpoints and the largest turn of
# its normal across a control edge (a fold or a wiggle between the
# vertices shows in those two), the fitted net's triangles, and the
# time. FIT_ARGS adds arguments (e.g. "--tolerance 1" to measure every
# fit, met or not).
# Usage: bash scripts/fit_sweep.sh [DATA_DIR]  (default: the test cache);
# LOOPSURF=path runs another build of the command.
set -uo pipefail
cd "$(dirname "$0")/.."
data=${1:-.cache/cgal/data/meshes}
max=${MAX_TRIANGLES:-10000}
if [ -z "${LOOPSURF:-}" ]; then
    cargo build --release -q -p loopsurf-cli || exit 2
    LOOPSURF=target/release/loopsurf
fi
out=$(mktemp --suffix=.obj)
trap 'rm -f "$out" "$out".*' EXIT
echo "| mesh | control faces | fit | worst vertex | worst midpoint | normal turn | fitted triangles | time |"
echo "|---|---|---|---|---|---|---|---|"
while read -r f n; do
    name=$(basename "$f")
    start=$(date +%s%N)
    log=$(RAYON_NUM_THREADS=1 timeout 90 "$LOOPSURF" fit "$f" --repair --hard-angle 30 ${FIT_ARGS:-} -o "$out" 2>&1)
    rc=$?
    secs=$(awk -v ns=$(( $(date +%s%N) - start )) 'BEGIN { printf "%.1f", ns / 1e9 }')
    if [ $rc -eq 124 ]; then
        echo "| $name | $n | over 90 s | | | | | |"
        continue
    fi
    if [ $rc -ne 0 ]; then
        miss=$(echo "$log" | grep -oP 'is \K[0-9.e-]+(?= from it)')
        if [ -n "$miss" ]; then
            echo "| $name | $n | missed | $miss | | | | ${secs} s |"
        else
            echo "| $name | $n | failed: $(echo "$log" | tail -1 | cut -c1-100) | | | | | |"
        fi
        continue
    fi
    worst=$(echo "$log" | grep -oP 'distance to the input vertices: max \K[0-9.e-]+')
    midpoint=$(echo "$log" | grep -oP 'distance to the input edge midpoints: max \K[0-9.e-]+')
    turn=$(echo "$log" | grep -oP 'across a control edge: \K[0-9.]+')
    tri=$(echo "$log" | grep -oP '^fitted net: [0-9]+ control points, \K[0-9]+')
    echo "| $name | $n | met | $worst | $midpoint | ${turn}° | $tri | ${secs} s |"
done < <(bash scripts/cgal_meshes.sh "$data" "$max")
