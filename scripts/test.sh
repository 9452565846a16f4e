#!/usr/bin/env bash
# Every test of the project, from a fresh Debian machine: installs what is
# missing (Debian packages through apt-get when root), extracts the CGAL demo
# meshes into an ignored cache, then runs the cargo tests (release mode: the
# numerics are heavy) and, once the C/C++/Fortran harness exists, ctest.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(cmake g++ gfortran pkgconf libopenmesh-dev libosd-dev openmpi-bin libopenmpi-dev libcgal-demo)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    if [ "$(id -u)" -eq 0 ]; then
        echo "installing: ${missing[*]}"
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
    else
        echo "missing Debian packages: ${missing[*]} (run this script as root, or apt-get install them)" >&2
        exit 1
    fi
fi

# Real legacy meshes (pig, cow, fandisk, bunny00, ...) from libcgal-demo
# (the tests extract them too, and fail without them unless
# LOOPSURF_SKIP_DATA=1).
cache=.cache/cgal
if [ ! -f "$cache/data/meshes/bunny00.off" ]; then
    mkdir -p "$cache"
    tar -xzf /usr/share/doc/libcgal-dev/data.tar.gz -C "$cache" data/meshes
fi

# meshio, from PyPI, so the curved-mesh and binary .vtu tests also check
# that it reads our .msh and .vtu files (they fail without it unless
# LOOPSURF_SKIP_DATA=1 asks to skip).
if ! python3 -c "import meshio" 2>/dev/null; then
    python3 -m pip install --quiet meshio >/dev/null 2>&1 || echo "meshio could not be installed: the tests that check our files with it will fail (LOOPSURF_SKIP_DATA=1 skips them)"
fi

# gmsh, from PyPI, which tetrahedralizes the volumes our meshes bound: a
# surface that crosses itself is refused (the volume test fails without it
# unless LOOPSURF_SKIP_DATA=1 asks to skip).
if ! python3 -c "import gmsh" 2>/dev/null; then
    python3 -m pip install --quiet gmsh >/dev/null 2>&1 || echo "gmsh could not be installed: the volume test will fail (LOOPSURF_SKIP_DATA=1 skips it)"
fi

cargo test --workspace --release

if [ -f CMakeLists.txt ]; then
    cmake -S . -B target/cmake -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build target/cmake -j 2
    ctest --test-dir target/cmake --output-on-failure
fi
