"""Merges the pieces of a .pvtu on their global node ids and checks that
the result is the reference .vtu, bit for bit: every piece's node is the
reference's node of its global id (coordinates compared as bits), every
reference node is in some piece, and the pieces' triangles, renumbered by
global id, are the reference's triangles, each exactly once. The files
are read with meshio, which shares no code with the writers.

Usage: merge_pieces.py REFERENCE.vtu PIECES.pvtu"""
import os
import sys
import xml.etree.ElementTree as ET

try:
    import meshio
    import numpy as np
except ImportError as e:
    if os.environ.get("LOOPSURF_SKIP_DATA") == "1":
        print(f"skipped: {e} (LOOPSURF_SKIP_DATA=1)")
        sys.exit(0)
    sys.exit(f"meshio is missing ({e}): pip install meshio, or LOOPSURF_SKIP_DATA=1 to skip")


def fail(message):
    sys.exit(f"merge_pieces: {message}")


def main(ref_path, pvtu):
    ref = meshio.read(ref_path)
    points = ref.points
    triangles = ref.cells_dict["triangle"].astype(np.int64)
    sources = [p.get("Source") for p in ET.parse(pvtu).getroot().iter("Piece")]
    if not sources:
        fail(f"{pvtu} names no piece")
    seen = np.zeros(len(points), dtype=np.int64)
    merged = []
    for source in sources:
        piece = meshio.read(os.path.join(os.path.dirname(pvtu), source))
        # (n,) or, where the piece says NumberOfComponents="1", (n, 1).
        ids = piece.point_data["GlobalNodeId"].astype(np.int64).reshape(-1)
        if len(ids) and (ids.min() < 0 or ids.max() >= len(points)):
            fail(f"{source}: a global id outside 0..{len(points) - 1}")
        if len(np.unique(ids)) != len(ids):
            fail(f"{source}: a global id given to two of its nodes")
        if not np.array_equal(piece.points.view(np.uint64), points[ids].view(np.uint64)):
            bad = np.nonzero((piece.points != points[ids]).any(axis=1))[0]
            fail(f"{source}: node {bad[0]} (global {ids[bad[0]]}) is not the reference's, bit for bit")
        seen[ids] += 1
        if "triangle" in piece.cells_dict:
            merged.append(ids[piece.cells_dict["triangle"].astype(np.int64)])
    if (seen == 0).any():
        fail(f"node {np.nonzero(seen == 0)[0][0]} of the reference is in no piece")
    merged = np.concatenate(merged) if merged else np.zeros((0, 3), dtype=np.int64)
    if len(merged) != len(triangles):
        fail(f"{len(merged)} triangles in the pieces, {len(triangles)} in the reference")
    order = lambda t: t[np.lexsort(t.T[::-1])]
    if not np.array_equal(order(merged), order(triangles)):
        fail("the pieces' triangles are not the reference's")
    shared = int((seen > 1).sum())
    print(f"{len(sources)} pieces: {len(merged)} triangles and {len(points)} nodes "
          f"({shared} on borders between pieces), the reference bit for bit")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
