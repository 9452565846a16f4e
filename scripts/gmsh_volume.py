"""Tetrahedralizes the volume a closed surface mesh bounds, with gmsh
(from PyPI): the client test that a surface mesh is fit for a volume
mesher. Prints the tetrahedron count; exits 1 with gmsh's error (for a
surface that crosses itself: "PLC Error: A segment and a facet
intersect") when gmsh refuses.

Usage: python3 scripts/gmsh_volume.py SURFACE.stl
"""
import sys

import gmsh

gmsh.initialize(["-nopopup"])
gmsh.option.setNumber("General.Terminal", 0)
gmsh.merge(sys.argv[1])
surfaces = [tag for _, tag in gmsh.model.getEntities(2)]
loop = gmsh.model.geo.addSurfaceLoop(surfaces)
gmsh.model.geo.addVolume([loop])
gmsh.model.geo.synchronize()
try:
    gmsh.model.mesh.generate(3)
except Exception as error:  # gmsh raises a bare Exception
    print(f"gmsh refused {sys.argv[1]}: {error}", file=sys.stderr)
    sys.exit(1)
_, tags, _ = gmsh.model.mesh.getElements(3)
print(sum(len(t) for t in tags))
gmsh.finalize()
