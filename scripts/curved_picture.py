#!/usr/bin/env python3
"""Draws curved (Lagrange) surface meshes side by side as one SVG: each
element cut along its node lattice into pieces shaded by their normals,
its edges drawn as the curves its map makes of them. Flat P1 triangles show
their facets; curved elements with nodes on the surface look smooth.
Reads loopsurf's ASCII .vtu (VTK_TRIANGLE 5, VTK_LAGRANGE_TRIANGLE 69).
Standard library only.

    python3 scripts/curved_picture.py OUT.svg "title" A.vtu ["title" B.vtu ...]

`scripts/pictures.sh` makes the picture in docs/high-order.md with it.
"""

import sys
import xml.etree.ElementTree as ET

from view3d import PANEL, VIEW, cross, dot, sub, unit

LIGHT = (-0.3, 0.5, 0.8)  # towards the light
EDGE_SAMPLES = 4  # points per node interval along a curved edge


def read_vtu(path):
    root = ET.parse(path).getroot()
    arrays = {}
    for a in root.iter("DataArray"):
        arrays[a.get("Name")] = a.text.split() if a.text else []
    flat = list(map(float, arrays["Points"]))
    points = [tuple(flat[i : i + 3]) for i in range(0, len(flat), 3)]
    conn = list(map(int, arrays["connectivity"]))
    offsets = list(map(int, arrays["offsets"]))
    types = list(map(int, arrays["types"]))
    cells, start = [], 0
    for end, t in zip(offsets, types):
        if t in (5, 69):
            cells.append(conn[start:end])
        start = end
    return points, cells


def lattice(k):
    """gmsh's (= VTK's) node order of the order-k triangle, as (i, j)."""
    if k == 0:
        return [(0, 0)]
    out = [(0, 0), (k, 0), (0, k)]
    out += [(i, 0) for i in range(1, k)] + [(k - i, i) for i in range(1, k)]
    out += [(0, k - i) for i in range(1, k)]
    if k >= 3:
        out += [(i + 1, j + 1) for i, j in lattice(k - 3)]
    return out


def basis(k, x, y):
    def factor(n, lam):
        p = 1.0
        for a in range(n):
            p *= (k * lam - a) / (a + 1)
        return p

    return [factor(i, x) * factor(j, y) * factor(k - i - j, 1 - x - y) for i, j in lattice(k)]


def order_of(n):
    k = 1
    while (k + 1) * (k + 2) // 2 < n:
        k += 1
    return k


def element_map(k, nodes, x, y):
    b = basis(k, x, y)
    return tuple(sum(w * p[d] for w, p in zip(b, nodes)) for d in range(3))


def pieces(points, cell):
    """The element's map at its node lattice, as k² small triangles (each
    shaded by its own normal), and its three edges as polylines through
    EDGE_SAMPLES points per node interval."""
    k = order_of(len(cell))
    nodes = [points[i] for i in cell]
    at = {}
    for j in range(k + 1):
        for i in range(k + 1 - j):
            at[i, j] = element_map(k, nodes, i / k, j / k)
    tris = []
    for j in range(k):
        for i in range(k - j):
            tris.append((at[i, j], at[i + 1, j], at[i, j + 1]))
            if i + j < k - 1:
                tris.append((at[i + 1, j], at[i + 1, j + 1], at[i, j + 1]))
    m = EDGE_SAMPLES * k if k > 1 else 1
    edges = [
        [element_map(k, nodes, i / m, 0) for i in range(m + 1)],
        [element_map(k, nodes, (m - i) / m, i / m) for i in range(m + 1)],
        [element_map(k, nodes, 0, (m - i) / m) for i in range(m + 1)],
    ]
    return tris, edges


def panel(points, cells, x0, title):
    view = unit(VIEW)
    right = unit(cross(view, (0.0, 0.0, 1.0)))
    up = cross(right, view)
    light = unit(LIGHT)
    xs = [dot(p, right) for p in points]
    ys = [dot(p, up) for p in points]
    scale = 0.9 * PANEL / max(max(xs) - min(xs), max(ys) - min(ys))
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2

    def screen(p):
        return (x0 + PANEL / 2 + scale * (dot(p, right) - cx), PANEL / 2 + 20 - scale * (dot(p, up) - cy))

    shapes = []
    for cell in cells:
        tris, edges = pieces(points, cell)
        depth = sum(dot(p, view) for t in tris for p in t) / (3 * len(tris))
        faces = []
        for a, b, c in tris:
            n = unit(cross(sub(b, a), sub(c, a)))
            if dot(n, view) >= 0:
                continue
            shade = 0.25 + 0.75 * max(0.0, dot(n, light))
            faces.append(([screen(a), screen(b), screen(c)], shade))
        if faces:
            shapes.append((depth, faces, [[screen(p) for p in e] for e in edges]))
    shapes.sort(key=lambda s: -s[0])
    out = [f'<text x="{x0 + PANEL / 2}" y="16" text-anchor="middle" font-family="sans-serif" font-size="14">{title}</text>']
    for _, faces, edges in shapes:
        for poly, shade in faces:
            g = int(90 + 150 * shade)
            fill = f"rgb({int(0.75 * g)},{int(0.85 * g)},{g})"
            pts = " ".join(f"{x:.1f},{y:.1f}" for x, y in poly)
            out.append(f'<polygon points="{pts}" fill="{fill}" stroke="{fill}" stroke-width="0.3"/>')
        for e in edges:
            pts = " ".join(f"{x:.1f},{y:.1f}" for x, y in e)
            out.append(f'<polyline points="{pts}" fill="none" stroke="#223" stroke-width="0.4"/>')
    return out


def main(argv):
    if len(argv) < 4 or len(argv) % 2:
        sys.exit(__doc__)
    out_path, pairs = argv[1], list(zip(argv[2::2], argv[3::2]))
    body = []
    for n, (title, path) in enumerate(pairs):
        points, cells = read_vtu(path)
        body += panel(points, cells, n * PANEL, title)
    width, height = PANEL * len(pairs), PANEL + 30
    with open(out_path, "w") as f:
        f.write(f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}">\n')
        f.write('<rect width="100%" height="100%" fill="white"/>\n')
        f.write("\n".join(body))
        f.write("\n</svg>\n")


if __name__ == "__main__":
    main(sys.argv)
