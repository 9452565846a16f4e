#!/bin/bash
# Remakes the pictures of the README and docs/: mesh quality (docs/remesh-viking.svg), the
# built-in Viking at 4% of its diagonal, the chart mesher against the
# remesher, each triangle coloured by its smallest angle; and curved
# elements (docs/curved-viking.svg), the Viking's adaptive mesh at
# tolerance 1e-2 as flat P1 and as P3 with every node on the surface.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -q -p loopsurf-cli
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
h=0.212 # 4% of the Viking control net's bounding-box diagonal (5.30)
target/release/loopsurf mesh --example viking --hard-angle 30 --size $h --charts --no-verify -o "$tmp/charts.off" >/dev/null
target/release/loopsurf mesh --example viking --hard-angle 30 --size $h --no-verify -o "$tmp/remesh.off" >/dev/null
mkdir -p docs
python3 scripts/mesh_picture.py docs/remesh-viking.svg \
    "--charts" "$tmp/charts.off" "remesher (default)" "$tmp/remesh.off"
echo "wrote docs/remesh-viking.svg"
for k in 1 3; do
    target/release/loopsurf mesh --example viking --hard-angle 30 --adapt curvature --tolerance 1e-2 \
        --order $k --no-verify -o "$tmp/p$k.vtu" >/dev/null
done
python3 scripts/curved_picture.py docs/curved-viking.svg \
    "P1: flat triangles" "$tmp/p1.vtu" "P3: every node on the surface" "$tmp/p3.vtu"
echo "wrote docs/curved-viking.svg"
