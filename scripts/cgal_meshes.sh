#!/bin/bash
# The OFF meshes of DATA_DIR with at most MAX triangles, one "path count"
# line each, in name order: what the sweeps run over.
# Usage: bash scripts/cgal_meshes.sh DATA_DIR MAX
set -uo pipefail
for f in "$1"/*.off; do
    # The triangle count: the second number of the OFF header.
    n=$(grep -v '^#' "$f" | tr -s ' \t\r\n' '\n' | grep -v '^$' | sed -n '3p')
    if [[ "$n" =~ ^[0-9]+$ ]] && [ "$n" -le "$2" ]; then
        echo "$f $n"
    fi
done
