#!/bin/bash
# The build at scale (docs/benchmarks.md): bunny00 refined three times (4.8M
# triangles) loaded as a control net, built on one thread, then its first
# snap; prints times and bytes per control triangle. Needs the CGAL meshes
# (scripts/test.sh extracts them) and about 12 GB of memory.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p loopsurf-cli -p loopsurf --example build_scale
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
target/release/loopsurf refine .cache/cgal/data/meshes/bunny00.off --levels 3 -o "$tmp/bunny00-3.ply" >/dev/null 2>&1
RAYON_NUM_THREADS=1 target/release/examples/build_scale "$tmp/bunny00-3.ply"
