#!/bin/bash
# The remesher on every CGAL demo mesh (up to MAX_TRIANGLES control
# triangles, 30 000 by default), as a user would first run it:
#   loopsurf mesh FILE --repair --hard-angle 40 --adapt curvature
# one thread, 120 s each, one markdown row per mesh: output triangles,
# time, min angle, mean-min, share below 20° (and how many of those the
# summary calls forced by features), the chord error, the pairs of
# triangles that cross (and of the control net's, where the mesh's do),
# and the warnings (folds of the net or of the surface, the tolerance
# missed). MESH_ARGS adds options to every run (e.g. --concave-seams).
# Usage: bash scripts/remesh_sweep.sh [DATA_DIR]  (default: the test cache)
set -uo pipefail
cd "$(dirname "$0")/.."
data=${1:-.cache/cgal/data/meshes}
max=${MAX_TRIANGLES:-30000}
cargo build --release -q -p loopsurf-cli || exit 2
out=$(mktemp --suffix=.off)
trap 'rm -f "$out"' EXIT
echo "| mesh | control faces | triangles | time | min | mean-min | below 20° (forced) | chord error | crossing pairs | warnings |"
echo "|---|---|---|---|---|---|---|---|---|---|"
while read -r f n; do
    name=$(basename "$f")
    log=$(RAYON_NUM_THREADS=1 timeout 120 target/release/loopsurf mesh "$f" --repair \
        --hard-angle 40 --adapt curvature ${MESH_ARGS:-} -o "$out" 2>&1)
    rc=$?
    if [ $rc -ne 0 ]; then
        why=$([ $rc -eq 124 ] && echo "over 120 s" || echo "$log" | tail -1 | cut -c1-120)
        echo "| $name | $n | failed: $why | | | | | | | |"
        continue
    fi
    tri=$(echo "$log" | grep -oP '^output: .*?, \K[0-9]+(?= triangles)')
    secs=$(echo "$log" | grep -oP '^output: .* in \K[0-9.]+(?= s)')
    min=$(echo "$log" | grep -oP '^angles: min \K[0-9.]+')
    mean=$(echo "$log" | grep -oP 'per-triangle minima \K[0-9.]+')
    below=$(echo "$log" | grep -oP '[0-9.]+% of triangles below 20° \(\K[0-9]+' )
    share=$(echo "$log" | grep -oP '\K[0-9.]+(?=% of triangles below 20°)')
    dev=$(echo "$log" | grep -oP '[0-9.e-]+(?= by snap)')
    crossing=$(echo "$log" | grep -oP '^crossings: \K([0-9]+|none)')
    in_net=$(echo "$log" | grep -oP 'the control net itself crosses in \K[0-9]+')
    [ -n "$in_net" ] && crossing="$crossing (net $in_net)"
    what=$(echo "$log" | grep -oP 'warning: \K(the net folds|triangles below 10° lie where the surface folds|chord tolerance)' | sort -u | tr '\n' ';')
    echo "| $name | $n | $tri | ${secs} s | ${min}° | ${mean}° | ${share}% ($below) | $dev | ${crossing/none/0} | ${what%;} |"
done < <(bash scripts/cgal_meshes.sh "$data" "$max")
