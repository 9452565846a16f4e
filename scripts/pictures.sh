#!/bin/bash
# Remakes the README's picture of mesh quality (docs/remesh-viking.svg):
# the built-in Viking at 4% of its diagonal, the chart mesher against the
# remesher, each triangle coloured by its smallest angle.
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
