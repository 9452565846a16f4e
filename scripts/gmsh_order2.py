#!/usr/bin/env python3
"""gmsh's order-2 mesh of an STL against loopsurf's curve of the same mesh.

The STL is the smooth surface sampled: the built-in torus control net
refined twice with every vertex at its limit position (`loopsurf refine
--levels 2 --limit`), 9 216 facets, the kind of file a user has. gmsh
meshes it (classifySurfaces + createGeometry, Frontal-Delaunay) at several
sizes and raises the mesh to order 2 (`setOrder(2)`), which puts the new
nodes on its discrete surface, the facets. `loopsurf curve --measure` then
reads gmsh's P2 file and reports, against loopsurf's limit surface of the
torus net (certified snap at 15 interior points per element): the
largest distance of gmsh's P2 mesh as it is, and of the same linear mesh
curved by loopsurf (vertices snapped, P2 nodes on the smooth surface).

Usage: python3 scripts/gmsh_order2.py   (needs `pip install gmsh`; run
from the repository root after `cargo build --release`)
"""
import math
import os
import re
import subprocess
import sys
import tempfile

import gmsh

LOOPSURF = os.path.join("target", "release", "loopsurf")
SIZES = [0.08, 0.04, 0.02, 0.01]  # fractions of the bounding-box diagonal


def run(args):
    out = subprocess.run([LOOPSURF] + args, check=True, capture_output=True, text=True)
    return out.stdout


def main():
    work = tempfile.mkdtemp(prefix="loopsurf-gmsh-")
    stl = os.path.join(work, "torus.stl")
    run(["refine", "--example", "torus", "--levels", "2", "--limit", "-o", stl])
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
    rows = []
    for h in SIZES:
        gmsh.clear()
        gmsh.merge(stl)
        gmsh.model.mesh.classifySurfaces(40 * math.pi / 180, True, True, math.pi)
        gmsh.model.mesh.createGeometry()
        xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(-1, -1)
        diag = math.dist((xmin, ymin, zmin), (xmax, ymax, zmax))
        gmsh.option.setNumber("Mesh.MeshSizeMin", h * diag)
        gmsh.option.setNumber("Mesh.MeshSizeMax", h * diag)
        gmsh.model.mesh.generate(2)
        gmsh.model.mesh.setOrder(2)
        path = os.path.join(work, f"gmsh-{h}.msh")
        gmsh.write(path)
        report = run(["curve", path, "--example", "torus", "--order", "2", "--measure",
                      "--max-move", "0.05", "-o", os.path.join(work, f"ours-{h}.msh")])
        m = re.search(r"as given\) ([0-9.e+-]+) of the diagonal .* curved ([0-9.e+-]+) at", report)
        tris = re.search(r"\(\d+ vertices, (\d+) triangles\)", report.splitlines()[1]).group(1)
        rows.append((h, tris, float(m.group(1)), float(m.group(2))))
    gmsh.finalize()
    print("| h | triangles | gmsh P2 (nodes on the STL) | loopsurf curve, P2 |")
    print("|---|---|---|---|")
    for h, tris, theirs, ours in rows:
        print(f"| {h:g} | {tris} | {theirs:.2e} | {ours:.2e} |")


if __name__ == "__main__":
    sys.exit(main())
