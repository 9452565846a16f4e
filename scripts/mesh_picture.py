#!/usr/bin/env python3
"""Draws surface meshes side by side as one SVG, each triangle filled by its
smallest angle (red below 20 degrees, through yellow, to green at 60), for the
README's picture of mesh quality. Standard library only.

    python3 scripts/mesh_picture.py OUT.svg "title" A.off ["title" B.off ...]

Orthographic view along VIEW (below), painter's order, back faces dropped.
`scripts/pictures.sh` makes the README's picture with it.
"""

import math
import sys

from view3d import PANEL, VIEW, cross, dot, sub, unit



def read_off(path):
    words = open(path).read().split()
    if words[0] == "OFF":
        words = words[1:]
    nv, nt = int(words[0]), int(words[1])
    pos = 3
    points = [tuple(map(float, words[pos + 3 * i : pos + 3 * i + 3])) for i in range(nv)]
    pos += 3 * nv
    tris = []
    for _ in range(nt):
        k = int(words[pos])
        tris.append(tuple(int(w) for w in words[pos + 1 : pos + 1 + k]))
        pos += 1 + k
    return points, tris


def min_angle(p, q, r):
    worst = 180.0
    for a, b, c in ((p, q, r), (q, r, p), (r, p, q)):
        u, v = sub(b, a), sub(c, a)
        d = math.sqrt(dot(u, u) * dot(v, v))
        if d == 0:
            return 0.0
        worst = min(worst, math.degrees(math.acos(max(-1.0, min(1.0, dot(u, v) / d)))))
    return worst


def colour(angle):
    """Red at 20 degrees or below, yellow at 40, green at 60."""
    t = max(0.0, min(1.0, (angle - 20.0) / 40.0))
    if t < 0.5:
        r, g = 220, int(60 + 2 * t * 160)
    else:
        r, g = int(220 - 2 * (t - 0.5) * 170), 220
    return f"#{r:02x}{g:02x}50"


def panel(points, tris, x0, title):
    view = unit(VIEW)
    right = unit(cross(view, (0.0, 0.0, 1.0)))
    up = cross(right, view)
    proj = [(dot(p, right), dot(p, up), dot(p, view)) for p in points]
    xs, ys = [p[0] for p in proj], [p[1] for p in proj]
    scale = 0.9 * PANEL / max(max(xs) - min(xs), max(ys) - min(ys))
    cx, cy = (max(xs) + min(xs)) / 2, (max(ys) + min(ys)) / 2
    shapes = []
    angles = []
    for t in tris:
        a, b, c = (points[i] for i in t[:3])
        angles.append(min_angle(a, b, c))
        if dot(cross(sub(b, a), sub(c, a)), view) >= 0:
            continue  # faces away
        depth = sum(proj[i][2] for i in t[:3]) / 3
        xy = " ".join(
            f"{x0 + PANEL / 2 + (proj[i][0] - cx) * scale:.0f},{PANEL / 2 + 30 - (proj[i][1] - cy) * scale:.0f}"
            for i in t[:3]
        )
        shapes.append((depth, xy, colour(angles[-1])))
    shapes.sort(key=lambda s: -s[0])
    body = ['<g stroke="#222" stroke-width="0.25">']
    body += [f'<polygon points="{xy}" fill="{fill}"/>' for _, xy, fill in shapes]
    body.append("</g>")
    mean = sum(angles) / len(angles)
    label = f"{title}: {len(tris)} triangles, min {min(angles):.1f}°, mean-min {mean:.1f}°"
    body.append(f'<text x="{x0 + 10}" y="18" font-family="sans-serif" font-size="13">{label}</text>')
    return body


def main():
    out, rest = sys.argv[1], sys.argv[2:]
    panels = list(zip(rest[0::2], rest[1::2]))
    width = PANEL * len(panels)
    parts = [
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{PANEL + 40}">',
        f'<rect width="{width}" height="{PANEL + 40}" fill="white"/>',
    ]
    for k, (title, path) in enumerate(panels):
        points, tris = read_off(path)
        parts += panel(points, tris, k * PANEL, title)
    parts.append("</svg>")
    with open(out, "w") as f:
        f.write("\n".join(parts) + "\n")


if __name__ == "__main__":
    main()
