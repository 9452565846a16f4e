"""Merges the .msh pieces of a run in gmsh, as a user would, and checks
that the result is the reference .vtu, bit for bit.

gmsh.merge of each piece into one model keeps a node on the border of two
pieces once per piece, under the one tag both give it (gmsh's
removeDuplicateNodes joins such copies, renumbering every node). The
check: every copy of a tag has the same coordinates, bit for bit; the
distinct tags are the reference's nodes (tag t is reference node t - 1,
coordinates as bits); and the triangles gmsh holds are the reference's,
each exactly once (two elements given one tag would lose one of them).
gmsh reads the pieces and meshio the reference, so neither shares code
with our writers.

Usage: merge_msh_pieces.py REFERENCE.vtu PIECE_0.msh [PIECE_1.msh ...]"""
import os
import sys

try:
    import gmsh
    import meshio
    import numpy as np
except ImportError as e:
    if os.environ.get("LOOPSURF_SKIP_DATA") == "1":
        print(f"skipped: {e} (LOOPSURF_SKIP_DATA=1)")
        sys.exit(0)
    sys.exit(f"gmsh or meshio is missing ({e}): pip install gmsh meshio, or LOOPSURF_SKIP_DATA=1 to skip")


def fail(message):
    sys.exit(f"merge_msh_pieces: {message}")


def main(ref_path, pieces):
    ref = meshio.read(ref_path)
    points = ref.points
    triangles = ref.cells_dict["triangle"].astype(np.int64)
    gmsh.initialize(["-noenv"])
    gmsh.option.setNumber("General.Terminal", 0)
    for piece in pieces:
        gmsh.merge(piece)
    tags, coords, _ = gmsh.model.mesh.getNodes()
    tags = np.asarray(tags, dtype=np.int64)
    bits = np.asarray(coords, dtype=np.float64).reshape(-1, 3).view(np.uint64)
    first = {}
    for tag, xyz in zip(tags, map(tuple, bits)):
        if first.setdefault(tag, xyz) != xyz:
            fail(f"two pieces give node tag {tag} different coordinates")
    shared = len(tags) - len(first)
    tags = np.fromiter(first.keys(), dtype=np.int64, count=len(first))
    coords = np.array(list(first.values()), dtype=np.uint64).reshape(-1, 3).view(np.float64)
    if len(tags) != len(points):
        fail(f"{len(tags)} distinct node tags in the pieces, {len(points)} nodes in the reference")
    ids = tags - 1
    if ids.min() < 0 or ids.max() >= len(points):
        fail(f"a node tag outside 1..{len(points)}")
    if not np.array_equal(coords.view(np.uint64), points[ids].view(np.uint64)):
        bad = np.nonzero((coords != points[ids]).any(axis=1))[0][0]
        fail(f"node tag {tags[bad]} is not the reference's node {ids[bad]}, bit for bit")
    element_tags, node_tags = gmsh.model.mesh.getElementsByType(2)
    merged = np.asarray(node_tags, dtype=np.int64).reshape(-1, 3) - 1
    if len(merged) != len(triangles):
        fail(f"{len(merged)} triangles merged, {len(triangles)} in the reference")
    order = lambda t: t[np.lexsort(t.T[::-1])]
    if not np.array_equal(order(merged), order(triangles)):
        fail("the merged triangles are not the reference's")
    gmsh.finalize()
    print(f"{len(pieces)} .msh pieces merged in gmsh: {len(merged)} triangles and {len(points)} nodes "
          f"({shared} copies on borders joined), the reference bit for bit")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
